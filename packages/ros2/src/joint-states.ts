/**
 * An arm's status stream (PROTOCOL §1, §8) as ROS 2 joint states: every position report, a pulse
 * width or a servo angle, turned into its URDF joint's value in ROS's units (radians, metres;
 * the profile's polarity and offset applied), named as the URDF names the joint. One JointState
 * per status payload that moved anything, once every servo has reported. Pure: fed payloads.
 */
import { jointFromServo, servoFromPwm, type Profile } from '@armtwin/robot';
import { exactPwmFromServo } from '@armtwin/motion';
import { createReader, type Frame, type Reader } from '@armtwin/protocol';
import type { JointStateMsg } from './wire.ts';

export class JointStateBuilder {
  /** Each servo's latest pulse width (exact: an angle report's pulse-equivalent), profile order. */
  readonly pwm: number[];
  /** Position reports for servos the profile does not have. */
  unknownServo = 0;
  private readonly index = new Map<number, number>();
  private readonly seen: boolean[];
  private changed = false;
  private stamp: number | undefined;
  private readonly reader: Reader;

  constructor(readonly profile: Profile) {
    profile.servos.forEach((s, i) => this.index.set(s.id, i));
    this.pwm = profile.servos.map(() => NaN);
    this.seen = profile.servos.map(() => false);
    const onFrame = (f: Frame) => this.onFrame(f);
    this.reader = createReader({
      onFrame,
      onGroup: (g) => {
        for (const f of g.frames) onFrame(f);
      },
    });
  }

  /** Whether every servo has reported at least once. */
  get complete(): boolean {
    return this.seen.every(Boolean);
  }

  /** Feeds one status payload; the joint state it leaves, if it moved anything and all are known. */
  feed(payload: string | Uint8Array): JointStateMsg | undefined {
    this.changed = false;
    this.stamp = undefined;
    this.reader.clearStamp();
    this.reader.feed(payload);
    if (!this.changed || !this.complete) return undefined;
    return this.jointState(this.stamp);
  }

  /** The joint state now (`stampMs` absent: the bridge stamps it when it publishes). */
  jointState(stampMs?: number): JointStateMsg {
    const servos = this.profile.servos;
    return {
      ...(stampMs === undefined ? {} : { stamp_ms: stampMs }),
      name: servos.map((s) => s.joint),
      position: servos.map((s, i) => jointFromServo(s, servoFromPwm(s, this.pwm[i]!))),
    };
  }

  private onFrame(f: Frame): void {
    if (f.type !== 'position' && f.type !== 'angle') return;
    const i = this.index.get(f.id);
    if (i === undefined) {
      this.unknownServo++;
      return;
    }
    const servo = this.profile.servos[i]!;
    this.pwm[i] = f.type === 'position' ? f.pwm : exactPwmFromServo(servo, f.deg);
    this.seen[i] = true;
    this.changed = true;
    if (f.time !== undefined) this.stamp = f.time;
  }
}
