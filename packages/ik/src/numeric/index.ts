/** Numeric IK for any serial chain (`@armtwin/robot` builds one from a profile and its URDF). */
export * from './mat4.ts';
export * from './chain-types.ts';
export { chainFk, chainFkFrames, createFkFrames, type FkFrames } from './fk.ts';
export * from './options.ts';
export { NumericIkSolver, createNumericIkResult, solveNumericIk } from './solver.ts';
