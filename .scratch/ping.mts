import mqtt from 'mqtt';
import pino from 'pino';
import { startSim } from '@armtwin/sim';
import { startNatsCluster } from '../tests/helpers/nats-cluster.ts';
const c = await startNatsCluster();
const sim = await startSim({ mqttUrl: c.mqttUrls(0), armId: 'p1', rate: 50, log: pino({ level: 'silent' }) });
const w = await mqtt.connectAsync(c.nodes[1]!.mqttUrl, { clientId: 'w' });
w.on('message', (t, p) => { const s = p.toString(); if (s.includes('PNG') || s.includes('ERR')) console.log(Date.now() % 100000, t, s.slice(0, 120)); });
await w.subscribeAsync('arm/p1/status', { qos: 0 });
for (let i = 0; i < 5; i++) { await w.publishAsync('arm/p1/control', `$PNG:${i}!`, { qos: 1 }); await new Promise((r) => setTimeout(r, 1000)); }
const cl = await mqtt.connectAsync(c.nodes[1]!.mqttUrl, { clientId: 'alice' });
await cl.publishAsync('arm/p1/claim/alice', 'take', { qos: 1 });
await new Promise((r) => setTimeout(r, 1000));
for (let i = 5; i < 8; i++) { await w.publishAsync('arm/p1/control', `$PNG:${i}!`, { qos: 1 }); await new Promise((r) => setTimeout(r, 1000)); }
await sim.stop(); await w.endAsync(); await cl.endAsync(); await c.dispose(); process.exit(0);
