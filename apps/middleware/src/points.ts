/**
 * Frames → InfluxDB line protocol, as ../../shared/PROTOCOL.md §6 specifies. Pure: no I/O,
 * no clock. Timestamps are written in microseconds (`precision=us`).
 *
 *   servo,arm=<arm>,id=<III> pwm=<int>i,angle=<deg>          from a position frame
 *   servo,arm=<arm>,id=<III> temp=<°C>,volt=<V>              from a health frame
 *   servo,arm=<arm>,id=<III> angle=<deg>                     from an angle frame (§8, no pwm)
 *   command,arm=<arm>,id=<III> pwm=<int>i,angle=<deg>,ms=<int>i   from a move on …/control
 *   command,arm=<arm>,id=<III> angle=<deg>,ms=<int>i         from an angle move on …/control
 *   ik,arm=<arm> code=<int>i,x=…,y=…,z=…[,a=…]               a $KMS request and its result
 *
 * Arm ids match `[a-z0-9-]{1,32}` and servo ids are three digits, so tag values never need
 * escaping.
 */
import {
  angleFromPwm,
  type AngleFrame,
  type AngleMoveFrame,
  type HealthFrame,
  type KmsFrame,
  type MoveFrame,
} from '@armtwin/protocol';

/** Microseconds since the epoch, the unit of every point's time. */
export type Micros = number;

export const servoId = (id: number): string => (id < 10 ? '00' : id < 100 ? '0' : '') + id;

/** Shortest exact float text; integral floats stay floats in InfluxDB (no `i`). */
const float = (v: number): string => String(v);

export const servoSeries = (arm: string, id: number): string =>
  `servo,arm=${arm},id=${servoId(id)}`;
export const commandSeries = (arm: string, id: number): string =>
  `command,arm=${arm},id=${servoId(id)}`;
export const ikSeries = (arm: string): string => `ik,arm=${arm}`;

/**
 * The field text of a position (`pwm=…i,angle=…`): a pure function of the pwm, so the text of
 * each pwm up to PWM_TEXT_CACHE is made once (a stream repeats a few hundred values).
 */
export function positionFields(pwm: number): string {
  const cacheable = Number.isInteger(pwm) && pwm >= 0 && pwm < PWM_TEXT_CACHE;
  const hit = cacheable ? pwmText[pwm] : undefined;
  if (hit !== undefined) return hit;
  const text = `pwm=${pwm}i,angle=${float(angleFromPwm(pwm))}`;
  if (cacheable) pwmText[pwm] = text;
  return text;
}
const PWM_TEXT_CACHE = 4096;
const pwmText: (string | undefined)[] = new Array<string | undefined>(PWM_TEXT_CACHE);

/** A bus servo's report (§8): the angle as it came, and no `pwm`. */
export const angleFields = (f: AngleFrame): string => `angle=${float(f.deg)}`;
export const healthFields = (f: HealthFrame): string =>
  `temp=${float(f.temp)},volt=${float(f.mv / 1000)}`;
export const commandFields = (f: MoveFrame): string => `${positionFields(f.pwm)},ms=${f.ms}i`;
/** A bus servo's command (§8): the target angle and time, and no `pwm`. */
export const angleCommandFields = (f: AngleMoveFrame): string =>
  `angle=${float(f.deg)},ms=${f.ms}i`;

/**
 * An `ik` point's fields: the result code (absent when the request never got one) and the
 * request's target (absent when the result came without a request this instance saw).
 */
export function ikFields(code: number | undefined, req: KmsFrame | undefined): string {
  const fields: string[] = [];
  if (code !== undefined) fields.push(`code=${code}i`);
  if (req) {
    fields.push(`x=${float(req.x)}`, `y=${float(req.y)}`, `z=${float(req.z)}`);
    if (req.alpha !== undefined) fields.push(`a=${float(req.alpha)}`);
  }
  return fields.join(',');
}

/** A line-protocol string field value: `"…"` with `\` and `"` escaped, line breaks as spaces. */
const stringField = (s: string): string =>
  `"${s.replace(/[\\"]/g, (c) => `\\${c}`).replace(/[\r\n]+/g, ' ')}"`;

/** The series of an arm's episodes (an arm id needs no escaping: ARM_ID_PATTERN). */
export const episodeSeries = (arm: string): string => `episode,arm=${arm}`;

/**
 * A field update of the episode that starts at `t` (its point's time): the task (and who marked
 * it) when it starts,
 * `stop` (epoch ms) when it stops, `discarded` when it is thrown away. InfluxDB merges the
 * fields of points of one series and time, so the episode is one point.
 */
export function episodeLine(
  arm: string,
  fields: { task?: string; by?: string; stop?: number; discarded?: true },
  t: Micros,
): string {
  const out: string[] = [];
  if (fields.task !== undefined) out.push(`task=${stringField(fields.task)}`);
  if (fields.by) out.push(`by=${stringField(fields.by.slice(0, 200))}`);
  if (fields.stop !== undefined) out.push(`stop=${Math.round(fields.stop)}i`);
  if (fields.discarded) out.push('discarded=true');
  return `${episodeSeries(arm)} ${out.join(',')} ${t}`;
}

/** The series of an arm's control events of one kind (a kind is one of AUDIT_KINDS: no escaping). */
export const auditSeries = (arm: string, kind: string): string => `audit,arm=${arm},kind=${kind}`;

/** One control event (`arm/{id}/audit`): who (`by`, '' = the plain topic) and what (`detail`). */
export function auditLine(series: string, by: string, detail: string, t: Micros): string {
  return `${series} by=${stringField(by)},detail=${stringField(detail.slice(0, 500))} ${t}`;
}

/** The profile an arm announced: its name (a models folder) and title. */
export function profileLine(series: string, name: string, title: string, t: Micros): string {
  return `${series} name=${stringField(name)},title=${stringField(title.slice(0, 200))} ${t}`;
}

/**
 * The clock of a servo's health points (`temp`, `volt`), apart from its positions' (`pwm`,
 * `angle`): the two kinds share no field, so a health point and a position of one time are
 * one InfluxDB point with both, never an overwrite, and neither is moved for the other. A
 * point's time then depends only on the history of its own kind: a position delivered again to
 * another middleware, which took the health report of the same ms first, lands on its first
 * copy (docs/cluster.md § Stored exactly once). Kinds that share a field (a position and an
 * angle frame: `angle`) share a clock.
 */
export const healthClock = (series: string): string => `${series} health`;

/**
 * Stamps within 1 ms of a series' last time are collisions, bumped; an older one is a late
 * arrival, kept at its own time (SeriesClock).
 */
export const COLLISION_WINDOW_US: Micros = 1000;

/**
 * A point's time in its series, so that InfluxDB never overwrites one report with another. The
 * `series` given is the point's clock: its series, or for a kind of point whose fields no other
 * kind of the series has, its own (healthClock).
 *
 * - a time ≤ the series' last time, and within COLLISION_WINDOW_US of it, becomes last + 1 µs.
 *   A 1 kHz stream whose `$TIM` stamps collide (two payloads in one ms, or a stamp repeated)
 *   keeps every point; the bump is at most a few µs and never crosses into the next real stamp
 *   unless > 1000 points per ms.
 * - the same report again (same stamp, same `fields`: a QoS 1 message delivered twice, e.g.
 *   re-sent across a broker move) gets the time of the first: it overwrites it with itself, also
 *   when another point of the series came in between within the window (a state report and a
 *   health report stamped in the same ms, then the state report again).
 * - a time older than that (a report that arrives late, behind newer ones: a redelivery after a
 *   broker move, or one queued on another broker) keeps its own time: a redelivered report
 *   overwrites its first copy with itself, a late one lands where it belongs. (Bumped to the
 *   series' end, it would be a second copy, at the wrong time.)
 * Memory: one entry per series (arm × servo × measurement), with the few points of its last ms.
 */
export class SeriesClock {
  /** Per series, its points within COLLISION_WINDOW_US of its last one (the last at the end). */
  private readonly recent = new Map<string, { stamp: Micros; at: Micros; fields: string }[]>();
  /** Times moved forward because they collided. */
  bumped = 0;

  /** The time for a point of `series` stamped `t`; `fields` (its values) says a repeat. */
  next(series: string, t: Micros, fields = ''): Micros {
    let recent = this.recent.get(series);
    if (recent === undefined) this.recent.set(series, (recent = []));
    const prev = recent[recent.length - 1];
    let at = t;
    if (prev !== undefined) {
      // A repeat of any point the window still holds, not only of the last: another report of
      // the series (a health report stamped in the same ms) may have come in between.
      if (fields !== '')
        for (const r of recent) if (r.stamp === t && r.fields === fields) return r.at;
      if (t < prev.at - COLLISION_WINDOW_US) return t; // late: its own time
      if (t <= prev.at) {
        at = prev.at + 1;
        this.bumped++;
      }
    }
    // Forget what has left the window (oldest first), in place; the first entry forgotten is
    // reused for this point, so a steady stream allocates nothing here.
    let gone = 0;
    while (gone < recent.length && recent[gone]!.at < at - COLLISION_WINDOW_US) gone++;
    const reuse = gone > 0 ? recent[0]! : undefined;
    if (gone > 0) {
      recent.copyWithin(0, gone);
      recent.length -= gone;
    }
    if (reuse) {
      reuse.stamp = t;
      reuse.at = at;
      reuse.fields = fields;
      recent.push(reuse);
    } else recent.push({ stamp: t, at, fields });
    return at;
  }

  get size(): number {
    return this.recent.size;
  }
}
