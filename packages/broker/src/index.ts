/**
 * The embedded MQTT broker (Aedes, in memory): `startBroker` (what `armtwin up` embeds),
 * `serveBroker` (what `armtwin broker` runs), its policy hooks and its security settings.
 */
export * from './auth.ts';
export * from './broker.ts';
export * from './security.ts';
export * from './serve-broker.ts';
