/**
 * The pure parts of the fleet section (../fleet.ts, issue 34 item 3), free of I/O: how many
 * simulator processes a step gets and which arms each hosts, how fast each arm reported,
 * what each arm lost between what its simulator published and what InfluxDB holds, a step's
 * verdict, and the highest step that lost nothing.
 */

/** A Node process is one thread: a step plans each simulator process at most this busy. */
export const PROCESS_BUDGET_MS = 500;

/** Below this share of the rate in messages an arm's loop is batching samples: it is behind. */
export const BEHIND = 0.8;

/**
 * Simulator processes for `arms` arms: one while one process can host them all within
 * `budgetMs` of CPU a second at `cpuMsPerArmS` (the cost measured on the step before; NaN when
 * none was: one process), otherwise as many as that needs, at most one per core; one per core
 * at once when the step before was `behind` (its loop sent its samples in batches).
 */
export function simProcesses(
  arms: number,
  cpuMsPerArmS: number,
  cores: number,
  behind = false,
  budgetMs = PROCESS_BUDGET_MS,
): number {
  const most = Math.max(1, Math.min(cores, arms));
  if (behind) return most;
  if (!(cpuMsPerArmS > 0)) return 1;
  const perProcess = Math.max(1, Math.floor(budgetMs / cpuMsPerArmS));
  return Math.min(most, Math.ceil(arms / perProcess));
}

/** Arms 1…arms split into `processes` consecutive ranges, as even as can be: [first, last]. */
export function splitArms(arms: number, processes: number): [number, number][] {
  const out: [number, number][] = [];
  let first = 1;
  for (let p = 0; p < processes; p++) {
    const n = Math.floor(arms / processes) + (p < arms % processes ? 1 : 0);
    if (n > 0) out.push([first, first + n - 1]);
    first += n;
  }
  return out;
}

/** Per arm: state samples a second between two counter snapshots (`atMs`, samples by arm). */
export function ratesByArm(
  a: { atMs: number; samples: Record<string, number> },
  b: { atMs: number; samples: Record<string, number> },
): Record<string, number> {
  const s = (b.atMs - a.atMs) / 1000;
  const out: Record<string, number> = {};
  for (const [arm, n] of Object.entries(b.samples)) out[arm] = (n - (a.samples[arm] ?? 0)) / s;
  return out;
}

export interface RateSummary {
  min: number;
  median: number;
  /** The arm that reported slowest. */
  slowest: string;
  /** Arms below `held` (the arms that did not hold the rate), and arms counted. */
  short: number;
  arms: number;
}

export function rateSummary(rates: Record<string, number>, held = 0): RateSummary {
  const e = Object.entries(rates).sort((x, y) => x[1] - y[1]);
  const short = e.filter(([, r]) => r < held).length;
  if (!e.length) return { min: NaN, median: NaN, slowest: '', short, arms: 0 };
  const mid = e.length / 2;
  const median = e.length % 2 ? e[Math.floor(mid)]![1] : (e[mid - 1]![1] + e[mid]![1]) / 2;
  return { min: e[0]![1], median, slowest: e[0]![0], short, arms: e.length };
}

/** What one arm's simulator published over its life: samples by kind and its servos. */
export interface ArmPublished {
  state: number;
  health: number;
  servos: number;
}

export interface ArmLoss {
  arm: string;
  /** Servo points its samples make (every sample: one point per servo). */
  published: number;
  stored: number;
}

export interface LossAccount {
  arms: number;
  published: number;
  stored: number;
  /** Points published and not stored, summed over the arms short of theirs. */
  lost: number;
  /** Points stored beyond what an arm published (stored twice, or another's). */
  extra: number;
  /** The arms whose stored count differs from their published one, the worst first. */
  uneven: ArmLoss[];
}

/**
 * Stored against published, arm by arm: a state or health sample of an arm with S servos makes S
 * servo points (an angle or a temperature each). An arm the store lacks stored nothing; an arm
 * the store has that did not publish counts as extra.
 */
export function lossByArm(
  published: Record<string, ArmPublished>,
  stored: Record<string, number>,
): LossAccount {
  const acc: LossAccount = { arms: 0, published: 0, stored: 0, lost: 0, extra: 0, uneven: [] };
  const arms = new Set([...Object.keys(published), ...Object.keys(stored)]);
  for (const arm of arms) {
    const p = published[arm];
    const want = p ? (p.state + p.health) * p.servos : 0;
    const got = stored[arm] ?? 0;
    acc.arms++;
    acc.published += want;
    acc.stored += got;
    if (got < want) acc.lost += want - got;
    if (got > want) acc.extra += got - want;
    if (got !== want) acc.uneven.push({ arm, published: want, stored: got });
  }
  acc.uneven.sort((a, b) => Math.abs(b.published - b.stored) - Math.abs(a.published - a.stored));
  return acc;
}

/** Below this share of the rate a step did not hold it (the loop catching up stays above). */
export const RATE_HELD = 0.95;

/** How long the store may take to catch up once the arms stop (as the ingest ramp's limit). */
export const drainLimitS = (flushS: number, publishS: number): number =>
  flushS + Math.max(2, 0.25 * publishS);

/**
 * A step's verdict: '' when every arm's points were stored once, the middleware dropped
 * nothing, the backlog was stored within its limit after the arms stopped, and every arm
 * reported at ≥ RATE_HELD of the rate; else why not (all reasons).
 */
export function stepWhy(f: {
  loss: LossAccount;
  dropped: number;
  rateHz: number;
  rates: RateSummary;
  drainS: number;
  drainLimitS: number;
}): string {
  const why: string[] = [];
  const { loss } = f;
  if (loss.lost)
    why.push(
      `${loss.lost} of ${loss.published} points lost (${loss.uneven.filter((u) => u.stored < u.published).length} of ${loss.arms} arms short)`,
    );
  if (loss.extra) why.push(`${loss.extra} points stored beyond what was published`);
  if (f.dropped) why.push(`${f.dropped} points dropped by the middleware`);
  if (f.drainS > f.drainLimitS)
    why.push(
      `stored ${f.drainS.toFixed(1)} s after the arms stopped (limit ${f.drainLimitS.toFixed(1)} s)`,
    );
  if (!(f.rates.min >= RATE_HELD * f.rateHz))
    why.push(
      `simulators below ${f.rateHz} Hz: ${f.rates.short} of ${f.rates.arms} arms under ${(RATE_HELD * f.rateHz).toFixed(1)} Hz, slowest ${f.rates.slowest} ${f.rates.min.toFixed(1)} Hz, median ${f.rates.median.toFixed(1)} Hz`,
    );
  return why.join('; ');
}

/**
 * Whether a failed step is run again with its arms spread over one process per core: only when
 * it lost nothing and failed by the simulators' rate alone, in fewer processes than cores.
 */
export function spreadAgain(
  step: { why: string; lost: number; extra: number; processes: number },
  cores: number,
): boolean {
  const onlyRate = step.why !== '' && step.why.split('; ').every((w) => w.startsWith('simulators'));
  return onlyRate && step.lost === 0 && step.extra === 0 && step.processes < cores;
}

/** The last step that passed before the first that failed (undefined when the first failed). */
export function highestHeld<T extends { pass: boolean }>(steps: T[]): T | undefined {
  let best: T | undefined;
  for (const s of steps) {
    if (!s.pass) break;
    best = s;
  }
  return best;
}
