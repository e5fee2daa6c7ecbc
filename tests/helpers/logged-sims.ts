/**
 * Simulated arms (`@armtwin/sim`'s `startSim`) for a test that counts what they sent: each at
 * 50 Hz with health at 10 Hz (every health report shares its ms with a state report, as a
 * re-sent pair taken by two middlewares needs to show a report stored twice), logging into kept
 * lines; each sim's last line ("sim stopped") says how many status messages it handed to its
 * client, and its runner counts the state samples and health payloads it made.
 */
import pino from 'pino';
import { startSim, type Sim } from '@armtwin/sim';

export interface SimLog {
  log: pino.Logger;
  /** Every line logged, as written. */
  lines: string[];
}

/** A pino logger (info and up) that keeps its lines. */
export function keptSimLog(): SimLog {
  const lines: string[] = [];
  const log = pino({ level: 'info' }, { write: (line: string) => void lines.push(line) });
  return { log, lines };
}

/** Starts one sim per arm into `sims`, arm `i` on the broker list `mqttUrlOf(i)`. */
export async function startLoggedSims(
  arms: readonly string[],
  mqttUrlOf: (i: number) => string,
  { log }: SimLog,
  sims: Map<string, Sim>,
): Promise<void> {
  for (const [i, arm] of arms.entries())
    sims.set(
      arm,
      await startSim({
        mqttUrl: mqttUrlOf(i),
        armId: arm,
        rate: 50,
        // Health at 10 Hz: every health report shares its ms with a state report, as a
        // re-sent pair taken by two middlewares needs to show a report stored twice.
        healthRate: 10,
        log,
        onFirst: (kind, message) => log.warn({ arm, kind }, message),
      }),
    );
}

/** Stops every arm's sim (removed from `sims`); the state samples and health payloads each made. */
export async function stopAndCount(
  arms: readonly string[],
  sims: Map<string, Sim>,
): Promise<{ published: Map<string, number>; healthSent: Map<string, number> }> {
  const published = new Map<string, number>();
  const healthSent = new Map<string, number>();
  for (const arm of arms) {
    const sim = sims.get(arm)!;
    await sim.stop();
    sims.delete(arm);
    published.set(arm, sim.runner!.counters.stateSamples);
    healthSent.set(arm, sim.runner!.counters.healthPayloads);
  }
  return { published, healthSent };
}

/** The status messages the stopped sims handed to their clients, from their "sim stopped" lines. */
export function statusMessagesSent(lines: readonly string[]): number {
  return lines
    .filter((l) => l.includes('"sim stopped"'))
    .map((l) => (JSON.parse(l) as { statusMessages: number }).statusMessages)
    .reduce((n, m) => n + m, 0);
}
