/** @armtwin/thermal: each servo's thermal model, its fit, early warning and prediction. No I/O. */
export * from './thermal-model.ts';
export * from './thermal-fit.ts';
export * from './thermal-watch.ts';
export * from './thermal-alert.ts';
export * from './thermal-predict.ts';
export * from './thermal-trace.ts';
