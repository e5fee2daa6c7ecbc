/** `armtwin robot import`'s pure core: a robot folder (URDF, meshes, profile.json) from a URDF. */
export * from './derive-profile.ts';
export * from './meshes.ts';
export * from './plan-import.ts';
export * from './limits.ts';
export * from './tool-rules.ts';
