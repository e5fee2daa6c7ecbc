/**
 * The fleet load (issue 34 item 3): N simulated arms in ONE process, each the real simulator
 * (`startSim` of @armtwin/sim, its own MQTT connection, status at `rate` Hz), ids
 * `<prefix>1 … <prefix>N`. Prints `{"ready":N,"startS":…}` once every arm is online, runs until
 * SIGTERM, then stops every arm (each says offline) and exits.
 * Usage: fleet.ts <mqtt url> <arms> <rate Hz> <id prefix>
 */
import { pino } from 'pino';
import { startSim, type Sim } from '@armtwin/sim';

const [url = '', armsS = '1', rateS = '50', prefix = 'fleet-'] = process.argv.slice(2);
const log = pino({ level: 'warn' });
const t0 = performance.now();
const sims: Sim[] = [];
// In tens: a few hundred connections at once would be a connect storm, not the steady state.
for (let i = 1; i <= Number(armsS); i += 10) {
  const ids = Array.from({ length: Math.min(10, Number(armsS) - i + 1) }, (_, k) => i + k);
  sims.push(
    ...(await Promise.all(
      ids.map((k) => startSim({ mqttUrl: url, armId: `${prefix}${k}`, log, rate: Number(rateS) })),
    )),
  );
}
process.stdout.write(
  `${JSON.stringify({ ready: sims.length, startS: (performance.now() - t0) / 1000 })}\n`,
);
process.once('SIGTERM', () => {
  void Promise.all(sims.map((s) => s.stop())).then(() => process.exit(0));
});
