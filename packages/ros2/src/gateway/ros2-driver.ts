/**
 * A ROS 2 arm as a driver of the controller core (@armtwin/controller): positions are the last
 * JointState (servo degrees, through the profile, turned into the pulse-equivalents the core
 * counts in); a goal becomes a JointTrajectory with one point, the goal joints at their goal in
 * the goal's time (0 = as fast as the profile's speed allows); a hold (a stop, the e-stop, the
 * deadman) is a trajectory to where the joints are now, sent at once; `PRAD` is answered from the
 * last joint state; `PRTV` is refused (a JointState carries no temperature or voltage). It
 * decides nothing: the core has already checked every goal. Pure.
 */
import type { ControllerDriver, Goal, ReadAnswer } from '@armtwin/controller';
import { jointFromServo, servoFromPwm, type Profile } from '@armtwin/robot';
import { exactPwmFromServo } from '@armtwin/motion';
import { encodeAngle } from '@armtwin/protocol';
import type { JointTrajectoryMsg } from '../wire.ts';

/** What the driver needs of the gateway core. */
export interface Ros2DriverTarget {
  /** The profile in force (an edited profile file replaces it: profile-follow). */
  readonly profile: Profile;
  /** '' while joint states arrive, else why the arm cannot be moved. */
  unready(): string;
  /** Each servo's last position, servo degrees (mm for a prismatic axis), profile order; NaN: none. */
  readonly positions: readonly number[];
  /** Sends a trajectory to the arm's controller. */
  trajectory(msg: JointTrajectoryMsg): void;
}

/** A hold's one point: the joints where they are, this soon (ms). */
export const HOLD_MS = 50;

export class Ros2Driver implements ControllerDriver {
  /** Until when the last trajectory runs, the driver's clock, ms. */
  private movingUntil = -Infinity;

  constructor(private readonly target: Ros2DriverTarget) {}

  private get profile(): Profile {
    return this.target.profile;
  }

  unready(): string {
    return this.target.unready();
  }

  pose(): number[] {
    return this.profile.servos.map((s, i) => exactPwmFromServo(s, this.target.positions[i]!));
  }

  moving(t: number): boolean {
    return t < this.movingUntil;
  }

  move(goals: readonly Goal[], t: number): void {
    if (goals.length === 0) return;
    const servos = this.profile.servos;
    const ms = Math.max(
      1,
      ...goals.map((g) => {
        if (g.ms > 0) return g.ms;
        const s = servos[g.i]!;
        const travel = Math.abs(servoFromPwm(s, g.pwm) - this.target.positions[g.i]!);
        return Number.isFinite(travel) ? (travel / s.maxSpeed) * 1000 : 0;
      }),
    );
    this.movingUntil = t + ms;
    this.target.trajectory({
      joint_names: goals.map((g) => servos[g.i]!.joint),
      points: [
        {
          positions: goals.map((g) =>
            jointFromServo(servos[g.i]!, servoFromPwm(servos[g.i]!, g.pwm)),
          ),
          time_from_start_ms: ms,
        },
      ],
    });
  }

  hold(indices: readonly number[], t: number): void {
    const known = indices.filter((i) => Number.isFinite(this.target.positions[i]));
    this.movingUntil = t;
    if (known.length === 0) return;
    const servos = this.profile.servos;
    this.target.trajectory({
      joint_names: known.map((i) => servos[i]!.joint),
      points: [
        {
          positions: known.map((i) => jointFromServo(servos[i]!, this.target.positions[i]!)),
          time_from_start_ms: HOLD_MS,
        },
      ],
    });
  }

  read(kind: 'position' | 'health', i: number): ReadAnswer {
    const s = this.profile.servos[i]!;
    if (kind === 'health') return { refused: `servo ${s.key}: no health in ROS 2 joint states` };
    const deg = this.target.positions[i]!;
    return Number.isFinite(deg)
      ? { frame: encodeAngle(s.id, deg) }
      : { refused: `servo ${s.key}: no joint state yet` };
  }
}
