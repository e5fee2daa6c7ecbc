/**
 * The simulated arm controller: `startSim` (what `armtwin sim` runs), the MQTT and serial
 * transports, the runner with its interlocks and faults, and robot profiles.
 */
export * from './bus-sim.ts';
export * from './faults.ts';
export * from './hand.ts';
export * from './mqtt-sim.ts';
export * from './options.ts';
export * from './profile.ts';
export * from './runner.ts';
export * from './serial-sim.ts';
export * from './start-sim.ts';
export * from './zones-follow.ts';
