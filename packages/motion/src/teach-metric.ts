/**
 * How far apart two poses are for teaching by showing (./teach.ts): each servo's error against
 * its tolerance and the tip's by FK, whether a pose is still, and the least time the servos
 * need between two poses. Pure: no I/O.
 */
import { servoFromPwm } from '@armtwin/robot';
import { tipPose, type MotionRobot } from './robot.ts';
import { topSpeed } from './joint-plan.ts';
import type { TeachOptions } from './teach.ts';

/** How far apart two poses are, as a fraction of the tolerance (≤ 1: within it). */
export class Metric {
  /** Servo units (deg or mm) per µs, and each servo's tolerance in them. */
  private readonly perUs: number[];
  private readonly tol: number[];
  readonly prismatic: boolean[];

  constructor(
    private readonly robot: MotionRobot,
    private readonly o: TeachOptions,
  ) {
    const servos = robot.profile.servos;
    this.perUs = servos.map((s) => Math.abs(servoFromPwm(s, 1600) - servoFromPwm(s, 1500)) / 100);
    this.prismatic = servos.map((s) => s.type === 'prismatic');
    this.tol = this.prismatic.map((p) => (p ? o.jointMm : o.jointDeg));
  }

  /** Servo i's error in its own units (deg or mm). */
  joint(i: number, a: number, b: number): number {
    return Math.abs(a - b) * this.perUs[i]!;
  }

  tipMm(a: readonly number[], b: readonly number[]): number {
    const p = tipPose(this.robot, a);
    const r = tipPose(this.robot, b);
    return Math.hypot(p.x - r.x, p.y - r.y, p.z - r.z);
  }

  /** Normalised distance: the worst of each servo's error / tolerance and the tip's. */
  ratio(a: readonly number[], b: readonly number[]): number {
    let worst = 0;
    for (let i = 0; i < a.length; i++)
      worst = Math.max(worst, this.joint(i, a[i]!, b[i]!) / this.tol[i]!);
    return Math.max(worst, this.tipMm(a, b) / this.o.tipMm);
  }

  /** The least time the servos need from one pose to the other at their top speed, ms. */
  travelMs(a: readonly number[], b: readonly number[]): number {
    let ms = 0;
    for (let i = 0; i < a.length; i++)
      ms = Math.max(ms, Math.abs(a[i]! - b[i]!) / topSpeed(this.robot, i, 1));
    return ms;
  }

  /** Whether every servo is within the `still` limits of the other pose. */
  still(a: readonly number[], b: readonly number[]): boolean {
    for (let i = 0; i < a.length; i++) {
      const lim = this.prismatic[i] ? this.o.stillMm : this.o.stillDeg;
      if (this.joint(i, a[i]!, b[i]!) > lim) return false;
    }
    return true;
  }
}
