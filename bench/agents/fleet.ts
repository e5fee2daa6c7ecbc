/**
 * The fleet load (issue 34 item 3): N simulated arms in ONE process, each the real simulator
 * (`startSim` of @armtwin/sim, its own MQTT connection, status at `rate` Hz), ids
 * `<prefix>1 … <prefix>N`. Prints `{"ready":N,"startS":…}` once every arm is online, runs until
 * SIGTERM, then stops every arm (each says offline) and exits.
 * `<mqtt url>` may hold several broker lists separated by `;` (a cluster's nodes, each list
 * starting at another node): arm k takes list (k − 1) mod their count. With `<counts file>`,
 * the state reports each arm made are written there as JSON (`{"<id>": n, …}`) once stopped.
 * Usage: fleet.ts <mqtt url> <arms> <rate Hz> <id prefix> [<counts file>]
 */
import fs from 'node:fs';
import { pino } from 'pino';
import { startSim, type Sim } from '@armtwin/sim';

const [url = '', armsS = '1', rateS = '50', prefix = 'fleet-', countsFile] = process.argv.slice(2);
const lists = url.split(';');
const log = pino({ level: 'warn' });
const t0 = performance.now();
const sims = new Map<string, Sim>();
// In tens: a few hundred connections at once would be a connect storm, not the steady state.
for (let i = 1; i <= Number(armsS); i += 10) {
  const ids = Array.from({ length: Math.min(10, Number(armsS) - i + 1) }, (_, k) => i + k);
  const started = await Promise.all(
    ids.map((k) =>
      startSim({
        mqttUrl: lists[(k - 1) % lists.length]!,
        armId: `${prefix}${k}`,
        log,
        rate: Number(rateS),
      }),
    ),
  );
  ids.forEach((k, j) => sims.set(`${prefix}${k}`, started[j]!));
}
process.stdout.write(
  `${JSON.stringify({ ready: sims.size, startS: (performance.now() - t0) / 1000 })}\n`,
);
process.once('SIGTERM', () => {
  void Promise.all([...sims.values()].map((s) => s.stop())).then(() => {
    if (countsFile) {
      const counts = [...sims].map(([id, s]) => [id, s.runner?.counters.stateSamples ?? 0]);
      fs.writeFileSync(countsFile, JSON.stringify(Object.fromEntries(counts)));
    }
    process.exit(0);
  });
});
