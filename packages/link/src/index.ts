export * from './brokers.ts';
export * from './connectBrokers.ts';
export * from './joined-stream.ts';
export * from './perishable.ts';
export * from './probe.ts';
