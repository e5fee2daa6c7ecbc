/** URDF reading and the numeric IK's chain built from a profile and its URDF. */
export * from './urdf.ts';
export * from './build-chain.ts';
export * from './chain-from-urdf.ts';
export * from './link-transforms.ts';
