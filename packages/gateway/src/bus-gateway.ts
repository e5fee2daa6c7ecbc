/**
 * The bus gateway's logic, without sockets: it does for Dynamixel or Feetech servos what the
 * seed controller's firmware did for its own. At each line open it pings the profile's ids
 * (missing ones reported with `$ERR` and pinged again every `repingMs`), switches wide joints to
 * multi-turn, writes present positions as goals and turns torque on; then it reads positions
 * with SYNC READ at the state rate and temperature and voltage at the health rate, publishing
 * `$TIM`-stamped angle and health groups. Control frames go to the controller core
 * (@armtwin/controller: limits, floor and zones, `$KMS`, the rate limit, the deadman, the
 * e-stop), whose goals the bus carries out (`./bus-driver.ts`); a stop, the deadman or torque
 * going back on write the present position as the goal (`./bus-holds.ts`). One request on the half-duplex line at a time (`./bus-line.ts`). The bytes, the
 * clock, the timers and the publish function are injected.
 */
import type { Profile } from '@armtwin/robot';
import {
  jointsFromProfile,
  type ControlInput,
  type ControllerCore,
  type KeepOutCheck,
  type KmsSolver,
} from '@armtwin/controller';
import { driverControl } from '@armtwin/controller/mqtt';
import type { MotionRobot } from '@armtwin/motion';
import {
  armTopics,
  encodeControllerError,
  encodeTime,
  OPERATOR_LEASE_MS,
  type OperatorTimers,
  type OperatorWatch,
} from '@armtwin/protocol';
import type { BusProtocol, BusResult, ServoCalibration } from '@armtwin/servo-bus';
import { BusDriver } from './bus-driver.ts';
import { BusLine, type BusLineCounters } from './bus-line.ts';
import { BusReports, LOST_AFTER_MS } from './bus-reports.ts';
import { busCalibration, busJoints, type BusGoal, type BusJoint } from './bus-servos.ts';
import { goalsWrite } from './bus-writes.ts';
import { BusHolds } from './bus-holds.ts';

export interface BusGatewayIo extends OperatorTimers {
  publish(topic: string, payload: string, opts: { qos: 0 | 1; retain: boolean }): void;
  /** Writes to the serial line; false when it is not open. */
  write(data: Uint8Array): boolean;
  /** Unix epoch ms. */
  now(): number;
  /** Told the first time each kind of problem happens. */
  onFirst(kind: string, message: string): void;
}

export interface BusGatewayOptions {
  armId: string;
  protocol: BusProtocol;
  profile: Profile;
  /** Line speed, for the reply time-outs. */
  baudRate: number;
  /** Positions read and published per second. */
  stateRate: number;
  /** Temperatures and voltages read and published per second. */
  healthRate: number;
  /** A servo that did not answer is pinged again this often, ms. */
  repingMs: number;
  /** A servo that answered no read for this long (and 3 in a row at least) is lost, ms. */
  lostAfterMs: number;
  /** A beating operator is let go after this long without a `1`, ms (0 = only a `0`). */
  operatorLeaseMs: number;
  /** `$KMS` through the profile's IK (`numericKms` of @armtwin/controller); unset: `$KMS` is refused. */
  kms?: KmsSolver;
  /** The floor and keep-out zones (`zonesKeepOut`) checked before any goal is written. */
  keepOut?: KeepOutCheck;
  /** The planner's robot, for motion requests (start-bus-gateway.ts). */
  robot?: MotionRobot;
}

export const DEFAULT_BUS_GATEWAY_OPTIONS = {
  baudRate: 1_000_000,
  stateRate: 50,
  healthRate: 2,
  repingMs: 1000,
  lostAfterMs: LOST_AFTER_MS,
  operatorLeaseMs: OPERATOR_LEASE_MS,
} satisfies Partial<BusGatewayOptions>;

export class BusGatewayCore {
  readonly counters = {
    statePayloads: 0,
    healthPayloads: 0,
    goalWrites: 0,
    holds: 0,
    deadmanStops: 0,
    /** Servos found missing by a ping or a read (each time one goes missing). */
    missing: 0,
  };
  readonly operator: OperatorWatch;
  readonly joints: BusJoint[];
  /** The controller: frames in, goals to the bus out. */
  readonly controller: ControllerCore;
  /** The control input in front of it: reader, payload bound, rate limit. */
  readonly input: ControlInput;
  readonly reports = new BusReports();
  /** Servos that answer (others are pinged again). */
  readonly found = new Set<number>();
  private o: BusGatewayOptions;
  private readonly topics;
  private readonly line: BusLine;
  /** Hold, set-up and torque: goals where the servos are. */
  private readonly holds: BusHolds;
  private lineOpen = false;
  private brokerUp = false;
  private pollTimer: unknown;
  private nextHealthMs = 0;
  private nextPingMs = 0;

  constructor(
    options: Partial<BusGatewayOptions> & Pick<BusGatewayOptions, 'armId' | 'protocol' | 'profile'>,
    private readonly io: BusGatewayIo,
  ) {
    this.o = { ...DEFAULT_BUS_GATEWAY_OPTIONS, ...options };
    this.topics = armTopics(this.o.armId);
    this.joints = busJoints(this.o.profile);
    this.line = new BusLine(this.o.protocol, this.joints, this.o.baudRate, io);
    this.holds = new BusHolds({
      protocol: this.o.protocol,
      line: this.line,
      reports: this.reports,
      found: this.found,
      joint: (id) => this.joint(id),
      calibration: (id) => this.calibration(id),
    });
    ({
      controller: this.controller,
      input: this.input,
      operator: this.operator,
    } = driverControl(
      jointsFromProfile(this.o.profile),
      new BusDriver(this, this.joints),
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

  /** Last position read, servo degrees, by id. */
  get positions(): ReadonlyMap<number, number> {
    return this.reports.positions;
  }

  /** Last health read, by id. */
  get health(): ReadonlyMap<number, { temp: number; mv: number }> {
    return this.reports.health;
  }

  get lineCounters(): BusLineCounters {
    return this.line.counters;
  }

  /** The line is open and the servos found have been set up. */
  get ready(): boolean {
    return this.lineOpen && this.line.ready;
  }

  serialOpened(): void {
    this.lineOpen = true;
    this.line.reset();
    this.found.clear();
    this.presence();
    const ids = this.joints.map((j) => j.id);
    this.line.ping(ids, (found, missing) => {
      for (const id of found) this.found.add(id);
      this.reportMissing(missing);
      this.holds.setUp(found);
      this.line.markReady();
    });
    this.schedule();
  }

  serialClosed(): void {
    this.lineOpen = false;
    this.line.reset();
    this.io.clearTimeout(this.pollTimer);
    this.pollTimer = undefined;
    this.presence();
  }

  brokerConnected(connected: boolean): void {
    this.brokerUp = connected;
    if (connected) this.presence();
  }

  fromSerial(chunk: Uint8Array): void {
    this.line.fromSerial(chunk);
  }

  fromOperator(payload: Uint8Array | string): void {
    this.operator.receive(payload);
  }

  /** The planner's robot now (motion requests), when one was given. */
  get robot(): MotionRobot | undefined {
    return this.o.robot;
  }

  /** The last goal written to servo `id`, degrees. */
  goalOf(id: number): number | undefined {
    return this.reports.goalOf(id);
  }

  fromControl(payload: Uint8Array | string): void {
    const replies = this.input.receive(payload, this.io.now());
    if (replies.length) this.status(replies);
  }

  /** `arm/{id}/torque`: `1` torque on (goals = present positions first), `0` torque off. */
  fromTorque(payload: Uint8Array | string): void {
    const text = (typeof payload === 'string' ? payload : Buffer.from(payload).toString()).trim();
    if (text !== '0' && text !== '1') return;
    this.holds.torque(text === '1', this.ready);
  }

  /**
   * A new calibration of the same servos (the profile file rewritten by the HUD's calibration
   * wizard): polarity, offset and limits change at once, torque and goals stay as they are (the
   * arm holds; nothing moves; goals still queued in the old terms are dropped). Returns an error,
   * and changes nothing, when the ids differ or a joint would switch in or out of multi-turn
   * (that is set up with torque off, at start).
   */
  reconfigure(
    profile: Profile,
    kms?: KmsSolver,
    keepOut?: KeepOutCheck,
    robot?: MotionRobot,
  ): string {
    const next = busJoints(profile);
    const ids = (js: readonly BusJoint[]) => js.map((j) => String(j.id).padStart(3, '0')).join(' ');
    if (ids(next) !== ids(this.joints))
      return `profile ${profile.name} drives servos ${ids(next)}, not ${ids(this.joints)}: restart the gateway`;
    const turned = next.filter((j, i) => j.multiTurn !== this.joints[i]!.multiTurn);
    if (turned.length)
      return `servos ${ids(turned)} would switch multi-turn mode: restart the gateway`;
    this.line.dropGoals();
    this.joints.splice(0, this.joints.length, ...next);
    this.o = { ...this.o, profile, kms, keepOut, robot: robot ?? this.o.robot };
    this.line.recalibrate();
    this.reports.forgetGoals();
    this.controller.reconfigure(jointsFromProfile(profile), { kms, keepOut });
    return '';
  }

  /** Goals checked by the controller core: one sync write, after whatever is on the line now. */
  writeGoals(goals: BusGoal[]): void {
    this.counters.goalWrites++;
    this.reports.remember(goals);
    this.line.send(goalsWrite(this.o.protocol, goals, this.calibration), 'goal');
  }

  /** Stops `ids` where they are: goals = present positions, ahead of any queued goal. */
  hold(ids: number[]): void {
    this.counters.holds++;
    this.holds.hold(ids);
  }

  /** Publishes frames (already encoded) as one `$TIM`-stamped status payload. */
  status(frames: string[]): void {
    if (!this.brokerUp) return;
    const payload = encodeTime(Math.round(this.io.now())) + frames.join('');
    this.io.publish(this.topics.status, payload, { qos: 0, retain: false });
  }

  /** A servo's zero and direction on the bus (its profile polarity). */
  private readonly calibration = (id: number): ServoCalibration => busCalibration(this.joint(id));

  private joint(id: number): BusJoint {
    return this.joints.find((j) => j.id === id)!;
  }

  private reportMissing(missing: number[]): void {
    if (missing.length === 0) return;
    this.counters.missing += missing.length;
    const text = `missing servos ${missing.map((id) => String(id).padStart(3, '0')).join(' ')}`;
    this.io.onFirst('bus:missing', text);
    this.status([encodeControllerError(text)]);
  }

  private schedule(): void {
    this.io.clearTimeout(this.pollTimer);
    this.pollTimer = this.io.setTimeout(() => this.poll(), 1000 / this.o.stateRate);
  }

  private poll(): void {
    this.pollTimer = undefined;
    if (!this.lineOpen) return;
    this.schedule();
    if (!this.line.ready) return;
    const now = this.io.now();
    const ids = this.joints.map((j) => j.id).filter((id) => this.found.has(id));
    if (ids.length && !this.line.has('positions'))
      this.line.readPositions(ids, (r) => this.onPositions(r, ids));
    if (ids.length && now >= this.nextHealthMs && !this.line.has('health')) {
      this.nextHealthMs = now + 1000 / this.o.healthRate;
      this.line.readHealth(ids, (r) => this.onHealth(r, ids));
    }
    const lost = this.joints.map((j) => j.id).filter((id) => !this.found.has(id));
    if (lost.length && now >= this.nextPingMs && !this.line.has('ping')) {
      this.nextPingMs = now + this.o.repingMs;
      this.line.ping(lost, (back) => {
        for (const id of back) this.found.add(id);
        this.holds.setUp(back, false);
      });
    }
  }

  private onPositions(r: Extract<BusResult, { kind: 'positions' }>, asked: number[]): void {
    const group = this.reports.positionFrames(r);
    this.lose(asked, r.missing);
    if (!group) return;
    this.counters.statePayloads++;
    this.status([group]);
  }

  private onHealth(r: Extract<BusResult, { kind: 'health' }>, asked: number[]): void {
    const frames = this.reports.healthFrames(r);
    this.lose(asked, r.missing);
    if (frames.length === 0) return;
    this.counters.healthPayloads++;
    this.status(frames);
  }

  /**
   * Servos that answered no read for `lostAfterMs` (`BusReports.lost`): reported, left out of
   * the reads and pinged until they are back (then set up again: they may have lost power).
   */
  private lose(asked: number[], missing: number[]): void {
    const lost = this.reports.lost(asked, missing, this.io.now(), this.o.lostAfterMs);
    for (const id of lost) this.found.delete(id);
    this.reportMissing(lost);
  }

  private presence(): void {
    if (!this.brokerUp) return;
    this.io.publish(this.topics.online, this.lineOpen ? '1' : '0', { qos: 1, retain: true });
  }
}
