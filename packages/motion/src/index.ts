/**
 * @armtwin/motion: joint and Cartesian plans for any armtwin profile, the frames that stream
 * them, pose checking, execution with re-planning, motion requests and feedback, and the HUD's
 * command box. Pure: no I/O, no timers, no Node imports (runs in the browser and the simulator).
 */
export * from './options.ts';
export * from './plan.ts';
export * from './robot.ts';
export * from './joint-plan.ts';
export * from './cartesian-plan.ts';
export * from './frames.ts';
export * from './pose-check.ts';
export * from './floor.ts';
export * from './zones/index.ts';
export * from './codes.ts';
export * from './request.ts';
export * from './motion.ts';
export * from './execution.ts';
export * from './feedback.ts';
export * from './command.ts';
export * from './teach.ts';
