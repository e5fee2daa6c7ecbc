/**
 * `armtwin up`, the app that composes the twin: the embedded broker (@armtwin/broker), the
 * simulated arms (@armtwin/sim), the middleware (@armtwin/middleware) and the HUD's files on one
 * HTTP port. `runUp` is what the command calls; `startUp` takes loaded users and TLS.
 */
export * from './model-copies.ts';
export * from './parts.ts';
export * from './run-up.ts';
export * from './static-files.ts';
export * from './up.ts';
export * from './security-headers.ts';
export * from './so101-part.ts';
