/**
 * The edge gateway: a real controller on a serial line ⇄ MQTT, behind the controller core.
 * `startGateway` (what `armtwin gateway` runs), the socket-free `GatewayCore` and its
 * `LscDriver`, the self-reopening `SerialLink`, and `followProfile` (a gateway's profile
 * announced and its file followed; the ROS 2 gateway's too).
 */
export * from './bus-driver.ts';
export * from './bus-gateway.ts';
export * from './bus-line.ts';
export * from './bus-reports.ts';
export * from './bus-servos.ts';
export * from './bus-writes.ts';
export * from './gateway.ts';
export * from './lsc-driver.ts';
export * from './profile-follow.ts';
export * from './leader-teleop.ts';
export * from './serial-link.ts';
export * from './start-bus-gateway.ts';
export * from './start-gateway.ts';
export * from './start-leader-gateway.ts';
export * from './bus-doctor.ts';
