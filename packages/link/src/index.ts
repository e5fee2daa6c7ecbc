export * from './connectBrokers.ts';
export * from './probe.ts';
