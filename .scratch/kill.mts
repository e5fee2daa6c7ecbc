import mqtt from 'mqtt';
import pino from 'pino';
import { startSim } from '@armtwin/sim';
import { startNatsCluster } from '../tests/helpers/nats-cluster.ts';
const c = await startNatsCluster();
const first = await mqtt.connectAsync(c.nodes[1]!.mqttUrl, { clientId: 'first' });
await new Promise((r) => setTimeout(r, 1500));
const leader = (await c.stream('$MQTT_msgs'))!.leader; const v = c.nodes.findIndex((n) => n.name === leader);
console.log('leader', leader);
const logs: string[] = [];
const sim = await startSim({ mqttUrl: c.mqttUrls(v), armId: 'p1', rate: 50, log: pino({ level: 'info' }, { write: (l: string) => void logs.push(l) }), onFirst: (k, m) => console.log('onFirst', k, m) });
const w = await mqtt.connectAsync(c.nodes[(v + 1) % 3]!.mqttUrl, { clientId: 'w' });
w.on('message', (t, p) => { const s = p.toString(); if (s.includes('PNG')) console.log(Date.now() % 100000, 'echo', s.slice(0, 60)); });
await w.subscribeAsync('arm/p1/status', { qos: 0 });
await new Promise((r) => setTimeout(r, 2000));
await w.publishAsync('arm/p1/control', `$PNG:100!`, { qos: 1 });
await new Promise((r) => setTimeout(r, 1000));
console.log(Date.now() % 100000, 'kill', leader); await c.nodes[v]!.process.kill();
const consumers = async () => {
  for (const n of c.nodes.filter((x) => x.running)) {
    const r = await fetch(`${n.monitorUrl}/jsz?accounts=true&streams=true&consumers=true&config=true`); const j = await r.json() as any;
    const s = j.account_details?.[0]?.stream_detail?.find((d: any) => d.name === '$MQTT_msgs');
    if (s?.cluster?.leader !== n.name) continue;
    return (s.consumer_detail ?? []).filter((cd: any) => /p1\.control$/.test(cd.config?.filter_subject ?? '')).map((cd: any) => ({ name: cd.name, leader: cd.cluster?.leader, pending: cd.num_pending, ack: cd.num_ack_pending, delivered: cd.delivered?.stream_seq, push: cd.push_bound }));
  }
  return null;
};
for (let i = 0; i < 40; i++) {
  try { await w.publishAsync('arm/p1/control', `$PNG:${i}!`, { qos: 1 }); } catch (e) { console.log('pub err', (e as Error).message); }
  await new Promise((r) => setTimeout(r, 1500));
  if (i % 5 === 4) console.log(Date.now() % 100000, JSON.stringify(await consumers()));
}
console.log(logs.filter((l) => /move|connected/.test(l)).join(''));
await sim.stop(); await w.endAsync(); await c.dispose(); process.exit(0);
