export * from './password.ts';
export * from './roles.ts';
export * from './users.ts';
export * from './throttle.ts';
export * from './whoami.ts';
export * from './mosquitto-config.ts';
export * from './mosquitto-deploy.ts';
