/** Keep-out zones and self-collision: geometry, the arm's links, and the checks. */
export * from './geometry.ts';
export * from './arm-links.ts';
export * from './zones.ts';
export * from './keep-out-reason.ts';
