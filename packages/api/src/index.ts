export * from './history.ts';
export * from './whoami.ts';
export * from './episodes.ts';
