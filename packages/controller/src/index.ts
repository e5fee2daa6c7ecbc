/**
 * The one arm controller core (README.md): `ControllerCore` (frames → goals, replies, refusals),
 * `ControlInput` (reader, payload bound, rate limit), `MotionRequests`, the driver interface,
 * the rules (keep-out, `$KMS`) and the arbiter's keep-out audit. The MQTT binding of motion
 * requests is `@armtwin/controller/mqtt`.
 */
export * from './arbiter.ts';
export * from './audit.ts';
export * from './control-input.ts';
export * from './core.ts';
export * from './driver.ts';
export * from './joints.ts';
export * from './motion.ts';
export * from './rate-limit.ts';
export * from './refusal.ts';
export * from './rules.ts';
export * from './summary.ts';
