/** Numeric IK for any serial chain a profile and its URDF describe. */
export * from './mat4.ts';
export * from './urdf.ts';
export * from './chain.ts';
export { chainFk, chainFkFrames, createFkFrames, type FkFrames } from './fk.ts';
export * from './options.ts';
export { NumericIkSolver, createNumericIkResult, solveNumericIk } from './solver.ts';
export * from './target.ts';
