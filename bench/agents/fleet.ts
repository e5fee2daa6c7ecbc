/**
 * The fleet load (issue 34 item 3): arms `<prefix><first> … <prefix><last>` in ONE process, each
 * the real simulator (`startSim` of @armtwin/sim, its own MQTT connection, status at `rate` Hz).
 * Prints one JSON line each:
 * - `{"ready":N,"startS":…}` once every arm is started;
 * - on SIGUSR2, `{"atMs":…,"samples":{arm: n},"payloads":{arm: n},"messages":n}`: the state
 *   samples and state payloads each arm published so far, and the status messages of every kind
 *   all of them did, in this process's clock;
 * - on SIGTERM, after stopping every arm (each says offline; an arm whose stop still waits on
 *   the broker after 20 s is left), `{"published":{arm:{"state","health","servos"}}}`, then
 *   exits.
 * `<mqtt url>` may hold several broker lists separated by `;` (a cluster's nodes, each list
 * starting at another node): arm k takes list (k − 1) mod their count. With `<counts file>`,
 * the state samples each arm's runner made are also written there as JSON (`{"<id>": n, …}`)
 * once stopped (bench/cluster.ts compares them with what was stored).
 * Usage: fleet.ts <mqtt url> <first> <last> <rate Hz> <id prefix> [<counts file>]
 */
import fs from 'node:fs';
import { pino } from 'pino';
import { startSim, type Sim } from '@armtwin/sim';

const [url = '', firstS = '1', lastS = '1', rateS = '50', prefix = 'fleet-', countsFile] =
  process.argv.slice(2);
const lists = url.split(';');
// Logs go to stderr (the run's log file): stdout carries the JSON lines.
const log = pino({ level: 'warn' }, pino.destination(2));
const t0 = performance.now();
const sims: { arm: string; sim: Sim }[] = [];
const say = (o: unknown, then?: () => void) => process.stdout.write(`${JSON.stringify(o)}\n`, then);
// In tens: a few hundred connections at once would be a connect storm, not the steady state.
for (let i = Number(firstS); i <= Number(lastS); i += 10) {
  const ids = Array.from({ length: Math.min(10, Number(lastS) - i + 1) }, (_, k) => i + k);
  sims.push(
    ...(await Promise.all(
      ids.map(async (k) => {
        const arm = `${prefix}${k}`;
        const onFirst = (kind: string, message: string) => log.warn({ arm, kind }, message);
        const sim = await startSim({
          mqttUrl: lists[(k - 1) % lists.length]!,
          armId: arm,
          log,
          rate: Number(rateS),
          onFirst,
        });
        return { arm, sim };
      }),
    )),
  );
}
say({ ready: sims.length, startS: (performance.now() - t0) / 1000 });
process.on('SIGUSR2', () => {
  const samples: Record<string, number> = {};
  const payloads: Record<string, number> = {};
  let messages = 0;
  for (const { arm, sim } of sims) {
    samples[arm] = sim.publishedSamples?.state ?? 0;
    payloads[arm] = sim.published?.state ?? 0;
    const p = sim.published;
    messages += p ? p.state + p.health + p.reply : 0;
  }
  say({ atMs: performance.now(), samples, payloads, messages });
});
// A stop waits on the broker (the offline messages are QoS 1): one that is far behind would
// hold the step for minutes, so each arm gets this long, and what it had published still counts.
const STOP_WAIT_MS = 20_000;
process.once('SIGTERM', () => {
  let unstopped = 0;
  const stop = (sim: Sim) =>
    Promise.race([
      sim.stop().then(() => true),
      new Promise<boolean>((r) => setTimeout(() => r(false), STOP_WAIT_MS).unref()),
    ]).then((done) => void (done || unstopped++));
  void Promise.all(sims.map(({ sim }) => stop(sim))).then(() => {
    if (unstopped) log.warn({ unstopped }, `arms not stopped within ${STOP_WAIT_MS} ms`);
    const published: Record<string, { state: number; health: number; servos: number }> = {};
    for (const { arm, sim } of sims)
      published[arm] = {
        state: sim.publishedSamples?.state ?? 0,
        health: sim.publishedSamples?.health ?? 0,
        servos: sim.runner?.model.servos.count ?? 0,
      };
    if (countsFile) {
      const counts = sims.map(({ arm, sim }) => [arm, sim.runner?.counters.stateSamples ?? 0]);
      fs.writeFileSync(countsFile, JSON.stringify(Object.fromEntries(counts)));
    }
    say({ published }, () => process.exit(0));
  });
});
