/**
 * The edge gateway: a real controller on a serial line ⇄ MQTT. `startGateway` (what
 * `armtwin gateway` runs), the socket-free `GatewayCore`, and the self-reopening `SerialLink`.
 */
export * from './bus-driver.ts';
export * from './bus-gateway.ts';
export * from './bus-line.ts';
export * from './bus-reports.ts';
export * from './bus-servos.ts';
export * from './bus-writes.ts';
export * from './gateway.ts';
export * from './leader-teleop.ts';
export * from './serial-link.ts';
export * from './start-bus-gateway.ts';
export * from './start-gateway.ts';
export * from './start-leader-gateway.ts';
export * from './bus-doctor.ts';
