/**
 * `armtwin gateway --ros2`'s logic, without processes or sockets: a ROS 2 arm (its joint states
 * in, trajectories out) behind the one controller core (@armtwin/controller), which decides
 * everything: the lease, limits, floor and zones, `$KMS`, the rate limit, the deadman, the e-stop.
 *
 * - Joint states in: matched to the profile by joint name (./joint-match.ts; one without every
 *   profile joint is refused and counted, extra joints are listed once), kept as servo degrees,
 *   published at the state rate as one `$TIM`-stamped group of angle frames `#IIIA±ddd.dd!`
 *   (a prismatic axis: its pulse `#IIIPpppp!`).
 * - `arm/{id}/online` is `1` while joint states arrive, `0` once none has for `staleMs`; moves
 *   are refused meanwhile (`$ERR:ros2: no joint states!`).
 * - Control frames go to the core; its goals and holds become trajectories (./ros2-driver.ts).
 * - `reconfigure`: an edited profile file (@armtwin/gateway's `followProfile`: the HUD's Zones
 *   section or calibration wizard through `armtwin up`) is put in force without a restart, if it
 *   names the same servos on the same joints: limits, zones, `$KMS`, polarity and offsets.
 *
 * The clock, the timers and the outputs are injected.
 */
import {
  jointsFromProfile,
  type ControlInput,
  type ControllerCore,
  type KeepOutCheck,
  type KmsSolver,
} from '@armtwin/controller';
import { driverControl } from '@armtwin/controller/mqtt';
import { servoFromJoint, type Profile } from '@armtwin/robot';
import { exactPwmFromServo, type MotionRobot } from '@armtwin/motion';
import {
  ANGLE_DEG_MAX,
  armTopics,
  encodeAngle,
  encodeGroup,
  encodePosition,
  encodeTime,
  OPERATOR_LEASE_MS,
  type Clock,
  type OperatorWatch,
} from '@armtwin/protocol';
import type { JointStateMsg, JointTrajectoryMsg } from '../wire.ts';
import { matchJoints } from './joint-match.ts';
import { Ros2Driver, type Ros2DriverTarget } from './ros2-driver.ts';

export interface Ros2GatewayIo extends Clock {
  publish(topic: string, payload: string, opts: { qos: 0 | 1; retain: boolean }): void;
  /** Sends a trajectory to the ROS 2 arm. */
  trajectory(msg: JointTrajectoryMsg): void;
  /** Told the first time each kind of problem happens. */
  onFirst(kind: string, message: string): void;
}

export interface Ros2GatewayOptions {
  armId: string;
  profile: Profile;
  /** Positions published per second (the latest joint state), Hz. */
  stateRate: number;
  /** No joint state for this long and the arm is offline, ms. */
  staleMs: number;
  /** A beating operator is let go after this long without a `1`, ms (0 = only a `0`). */
  operatorLeaseMs: number;
  kms?: KmsSolver;
  keepOut?: KeepOutCheck;
  /** The planner's robot, for motion requests. */
  robot?: MotionRobot;
}

export const DEFAULT_ROS2_GATEWAY_OPTIONS = {
  stateRate: 50,
  staleMs: 500,
  operatorLeaseMs: OPERATOR_LEASE_MS,
} satisfies Partial<Ros2GatewayOptions>;

export const NO_JOINT_STATES_REPLY = 'ros2: no joint states';

export class Ros2GatewayCore implements Ros2DriverTarget {
  readonly counters = {
    jointStates: 0,
    badJointStates: 0,
    statePayloads: 0,
    trajectories: 0,
    deadmanStops: 0,
  };
  /** Each servo's last position, servo degrees (mm), profile order; NaN until the first joint state. */
  readonly positions: number[];
  readonly controller: ControllerCore;
  readonly input: ControlInput;
  readonly operator: OperatorWatch;
  private o: Ros2GatewayOptions;
  /** Each profile joint's last position as the arm gave it (rad or m), profile order; NaN: none. */
  private readonly jointPositions: number[];
  private readonly topics;
  private lastStateAt = -Infinity;
  private pending = false;
  private brokerUp = false;
  private online = false;
  private timer: unknown;

  constructor(
    options: Partial<Ros2GatewayOptions> & Pick<Ros2GatewayOptions, 'armId' | 'profile'>,
    private readonly io: Ros2GatewayIo,
  ) {
    this.o = { ...DEFAULT_ROS2_GATEWAY_OPTIONS, ...options };
    this.topics = armTopics(this.o.armId);
    this.positions = this.o.profile.servos.map(() => NaN);
    this.jointPositions = this.o.profile.servos.map(() => NaN);
    ({
      controller: this.controller,
      input: this.input,
      operator: this.operator,
    } = driverControl(
      jointsFromProfile(this.o.profile),
      new Ros2Driver(this),
      { kms: this.o.kms, keepOut: this.o.keepOut },
      io,
      {
        operatorLeaseMs: this.o.operatorLeaseMs,
        deadmanStopped: (replies) => {
          this.counters.deadmanStops++;
          this.status(replies);
        },
      },
    ));
  }

  get robot(): MotionRobot | undefined {
    return this.o.robot;
  }

  get profile(): Profile {
    return this.o.profile;
  }

  /**
   * Puts an edited profile in force (limits, zones, `$KMS`, polarity and offsets); '' when taken,
   * else why not: it must name the same servos on the same joints, in the same order.
   */
  reconfigure(
    profile: Profile,
    kms?: KmsSolver,
    keepOut?: KeepOutCheck,
    robot?: MotionRobot,
  ): string {
    const servos = (p: Profile) => p.servos.map((s) => `${s.id}:${s.joint}`).join(' ');
    if (servos(profile) !== servos(this.o.profile))
      return `profile ${profile.name} has servos ${servos(profile)}, not ${servos(this.o.profile)}: restart the gateway`;
    this.o = { ...this.o, profile, kms, keepOut, robot: robot ?? this.o.robot };
    profile.servos.forEach((s, i) => {
      const q = this.jointPositions[i]!;
      if (Number.isFinite(q)) this.positions[i] = servoFromJoint(s, q);
    });
    this.controller.reconfigure(jointsFromProfile(profile), { kms, keepOut });
    return '';
  }

  /** Starts the state loop. */
  start(): void {
    this.schedule();
  }

  stop(): void {
    this.io.clearTimeout(this.timer);
    this.timer = undefined;
    this.operator.reset();
  }

  /** A JointState from the arm; '' when taken, else why not (a profile joint missing). */
  fromJointState(msg: JointStateMsg): string {
    const m = matchJoints(this.o.profile, msg.name);
    if (m.missing.length) {
      this.counters.badJointStates++;
      const why = `joint state without ${m.missing.join(', ')} (profile ${this.o.profile.name})`;
      this.io.onFirst('ros2:missing-joints', why);
      return why;
    }
    if (m.extra.length)
      this.io.onFirst(
        'ros2:extra-joints',
        `joints not in the profile, ignored: ${m.extra.join(', ')}`,
      );
    this.o.profile.servos.forEach((s, i) => {
      const q = msg.position[m.index[i]!];
      if (q === undefined || !Number.isFinite(q)) return;
      this.jointPositions[i] = q;
      this.positions[i] = servoFromJoint(s, q);
    });
    this.counters.jointStates++;
    this.lastStateAt = this.io.now();
    this.pending = true;
    this.presence();
    return '';
  }

  unready(): string {
    return this.fresh() ? '' : NO_JOINT_STATES_REPLY;
  }

  trajectory(msg: JointTrajectoryMsg): void {
    this.counters.trajectories++;
    this.io.trajectory(msg);
  }

  brokerConnected(connected: boolean): void {
    this.brokerUp = connected;
    if (connected) {
      this.online = !this.fresh(); // forces the retained value out again
      this.presence();
    }
  }

  fromControl(payload: Uint8Array | string): void {
    const replies = this.input.receive(payload, this.io.now());
    if (replies.length) this.status(replies);
  }

  fromOperator(payload: Uint8Array | string): void {
    this.operator.receive(payload);
  }

  /** Publishes frames (already encoded) as one `$TIM`-stamped status payload. */
  status(frames: string[]): void {
    if (!this.brokerUp) return;
    this.io.publish(this.topics.status, encodeTime(Math.round(this.io.now())) + frames.join(''), {
      qos: 0,
      retain: false,
    });
  }

  private fresh(): boolean {
    return this.io.now() - this.lastStateAt <= this.o.staleMs;
  }

  private presence(): void {
    const now = this.fresh();
    if (now === this.online || !this.brokerUp) return;
    this.online = now;
    this.io.publish(this.topics.online, now ? '1' : '0', { qos: 1, retain: true });
  }

  private schedule(): void {
    this.timer = this.io.setTimeout(() => this.tick(), 1000 / this.o.stateRate);
  }

  private tick(): void {
    this.schedule();
    this.presence();
    if (!this.pending) return;
    this.pending = false;
    const frames: string[] = [];
    this.o.profile.servos.forEach((s, i) => {
      const v = this.positions[i]!;
      if (!Number.isFinite(v)) return;
      if (s.type === 'prismatic')
        frames.push(encodePosition(s.id, Math.round(exactPwmFromServo(s, v))));
      else if (Math.abs(v) <= ANGLE_DEG_MAX) frames.push(encodeAngle(s.id, v));
      else
        this.io.onFirst(
          'ros2:angle-range',
          `servo ${s.key} at ${v.toFixed(1)}° is beyond an angle frame`,
        );
    });
    if (frames.length === 0) return;
    this.counters.statePayloads++;
    this.status([encodeGroup(frames)]);
  }
}
