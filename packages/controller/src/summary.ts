/**
 * The arm's summary (docs/protocol.md § Fleets), kept beside the controller core for any driver:
 * it reads the status payloads the arm publishes (only their health reports and `$ERR`s: a
 * payload with neither is not parsed) and, when asked, makes the summary from the core: the
 * state and pose from its driver, the worst health level and the last `$ERR` from the payloads,
 * the holder given. Pure: times come in as arguments. Its MQTT binding is ./summary-mqtt.ts.
 */
import {
  createReader,
  healthSummary,
  type ArmSummary,
  type Frame,
  type SummaryJoint,
} from '@armtwin/protocol';
import type { ControllerCore } from './core.ts';
import type { Joint } from './joints.ts';

const V = 0x56;
const E = 0x45;
const mayMatter = (p: string | Uint8Array): boolean =>
  typeof p === 'string' ? p.includes('V') || p.includes('E') : p.includes(V) || p.includes(E);

const tenth = (x: number): number => Math.round(x * 10) / 10;

/** A joint's servo angle at pulse-equivalent `pwm` (the inverse of `pwmOfAngle`, which is affine). */
export function angleOfPwm(j: Joint, pwm: number): number {
  const a = j.pwmOfAngle(j.minDeg);
  const b = j.pwmOfAngle(j.maxDeg);
  if (a === b) return j.minDeg;
  return j.minDeg + ((pwm - a) / (b - a)) * (j.maxDeg - j.minDeg);
}

export class SummaryTracker {
  /** Status payloads read, and those parsed (they held a health report or an `$ERR`). */
  readonly counters = { payloads: 0, parsed: 0 };
  private readonly health: Record<number, { temp: number; mv: number }> = {};
  private level: ArmSummary['health'] = 'unknown';
  private alarm = '';
  private error: ArmSummary['error'] = null;
  /** While one payload is read: it held a health report, an `$ERR`. */
  private sawHealth = false;
  private sawError = false;
  private t = 0;
  private readonly reader = createReader({
    onFrame: (f) => this.frame(f),
    onGroup: (g) => {
      for (const f of g.frames) this.frame(f);
    },
  });

  /**
   * Reads one status payload the arm published at `t`. Returns whether it raised an alarm: the
   * worst health level changed, or a new `$ERR` came (the summary should go out at once).
   */
  note(payload: string | Uint8Array, t: number): boolean {
    this.counters.payloads++;
    if (!mayMatter(payload)) return false;
    this.counters.parsed++;
    this.t = t;
    this.sawHealth = this.sawError = false;
    const levelBefore = this.level;
    this.reader.reset();
    this.reader.feed(payload);
    if (this.sawHealth) {
      const s = healthSummary(this.health);
      this.level = s.level;
      this.alarm = s.alarm;
    }
    return this.level !== levelBefore || this.sawError;
  }

  /** The summary at `t`: state and pose from the core's driver, health and `$ERR` as read. */
  summary(core: ControllerCore, holder: string | null, t: number): ArmSummary {
    const d = core.driver;
    const why = d.unready();
    const pose = d.pose(t);
    const joints: SummaryJoint[] = core.joints.map((j, i) => ({
      id: j.id,
      deg: Number.isFinite(pose[i]) ? tenth(angleOfPwm(j, pose[i]!)) : NaN,
      min: tenth(j.minDeg),
      max: tenth(j.maxDeg),
    }));
    return {
      t: Math.round(t),
      state: why ? 'not-ready' : d.moving(t) ? 'moving' : 'still',
      why,
      health: this.level,
      alarm: this.alarm,
      holder,
      // An unknown position is left out (JSON has no NaN).
      joints: joints.filter((j) => Number.isFinite(j.deg)),
      error: this.error,
    };
  }

  private frame(f: Frame): void {
    if (f.type === 'health') {
      this.health[f.id] = { temp: f.temp, mv: f.mv };
      this.sawHealth = true;
    } else if (f.type === 'controllerError') {
      this.error = { t: Math.round(this.t), text: f.text };
      this.sawError = true;
    }
  }
}
