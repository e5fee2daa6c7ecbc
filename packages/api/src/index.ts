export * from './history.ts';
export * from './whoami.ts';
