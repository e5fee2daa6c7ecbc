/**
 * The servo bus as a driver of the controller core (@armtwin/controller): positions are the last
 * SYNC READ (servo degrees turned into the pulse-equivalents the core counts in, through the
 * profile), a goal becomes a goal position and the speed that arrives on time, a hold writes the
 * present positions as goals, and `PRAD` / `PRTV` are answered from the last reads. Pure.
 */
import { servoFromPwm } from '@armtwin/robot';
import type { ControllerDriver, Goal, ReadAnswer } from '@armtwin/controller';
import { exactPwmFromServo } from '@armtwin/motion';
import { encodeAngle, encodeHealth } from '@armtwin/protocol';
import { busGoal, type BusGoal, type BusJoint } from './bus-servos.ts';

/** What the driver needs of the gateway core. */
export interface BusDriverTarget {
  readonly ready: boolean;
  readonly positions: ReadonlyMap<number, number>;
  readonly health: ReadonlyMap<number, { temp: number; mv: number }>;
  readonly found: ReadonlySet<number>;
  /** The last goal written to servo `id`, degrees (undefined: none yet). */
  goalOf(id: number): number | undefined;
  writeGoals(goals: BusGoal[]): void;
  hold(ids: number[]): void;
}

export const NOT_READY_REPLY = 'gateway: serial line down';

/** A servo this far from its goal (degrees) is still on its way. */
export const BUS_ARRIVED_DEG = 0.5;

const id3 = (id: number) => String(id).padStart(3, '0');

export class BusDriver implements ControllerDriver {
  constructor(
    private readonly target: BusDriverTarget,
    private readonly joints: readonly BusJoint[],
  ) {}

  unready(): string {
    return this.target.ready ? '' : NOT_READY_REPLY;
  }

  pose(): number[] {
    return this.joints.map((j) => {
      const deg = this.target.positions.get(j.id);
      return deg === undefined ? NaN : exactPwmFromServo(j.servo, deg);
    });
  }

  moving(): boolean {
    return this.joints.some((j) => {
      const goal = this.target.goalOf(j.id);
      const at = this.target.positions.get(j.id);
      return goal !== undefined && at !== undefined && Math.abs(goal - at) > BUS_ARRIVED_DEG;
    });
  }

  move(goals: readonly Goal[]): void {
    const out = goals.map((g) => {
      const j = this.joints[g.i]!;
      const from = this.target.positions.get(j.id) ?? NaN;
      return busGoal(j, servoFromPwm(j.servo, g.pwm), g.ms, from);
    });
    if (out.length) this.target.writeGoals(out);
  }

  hold(indices: readonly number[]): void {
    if (!this.target.ready) return;
    this.target.hold(indices.map((i) => this.joints[i]!.id));
  }

  read(kind: 'position' | 'health', i: number): ReadAnswer {
    const id = this.joints[i]!.id;
    const refused = { refused: `servo ${id3(id)} not answering` };
    if (!this.target.found.has(id)) return refused;
    if (kind === 'position') {
      const deg = this.target.positions.get(id);
      return deg === undefined ? refused : { frame: encodeAngle(id, deg) };
    }
    const h = this.target.health.get(id);
    return h ? { frame: encodeHealth(id, h.temp, h.mv) } : refused;
  }
}
