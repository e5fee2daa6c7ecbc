/**
 * @armtwin/robot: a robot's description: its profile (format, parser, conversions, keep-out
 * zones, calibration), its URDF read into the numeric IK's chain, and the pure core of
 * `armtwin robot import`. No I/O (`./import-node` reads and writes files and zips).
 */
export * from './profile/index.ts';
export * from './urdf/index.ts';
export * from './import/index.ts';
