export * from './brokers.ts';
export * from './connectBrokers.ts';
export * from './probe.ts';
