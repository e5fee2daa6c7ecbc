/**
 * The edge gateway's logic, without sockets: serial bytes → protocol reader → frames
 * re-encoded into one `$TIM`-stamped status payload per serial chunk (groups stay groups);
 * presence `1` only while the serial line is open and the broker connected. Control payloads go
 * through the controller core (@armtwin/controller: the payload bound, the rate limit, limits,
 * the floor, keep-out zones and self-collision of the robot profile, `$KMS` through its IK, the
 * e-stop) before the firmware sees them; what passes is written to the line as frames the
 * firmware executes itself (./lsc-driver.ts), a refusal is answered `$ERR` on status as on the
 * simulator and the bus. The deadman (the operator's `0`, or a beating operator whose lease ran
 * out) writes `#255PDST!` while the arm moves, answered `$ERR:deadman stop!`. The publish and
 * write functions, the clock and the timers are injected.
 */
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
  createReader,
  encodeFrame,
  encodeTime,
  OPERATOR_LEASE_MS,
  type Frame,
  type OperatorTimers,
  type OperatorWatch,
} from '@armtwin/protocol';
import type { Profile } from '@armtwin/robot';
import { LscDriver } from './lsc-driver.ts';

export interface GatewayIo extends OperatorTimers {
  publish(topic: string, payload: Buffer | string, opts: { qos: 0 | 1; retain: boolean }): void;
  /** Writes to the serial line; false when it is not open. */
  write(data: Buffer): boolean;
  /** Unix epoch ms. */
  now(): number;
  /** Told the first time each kind of problem happens. */
  onFirst(kind: string, message: string): void;
}

export interface GatewayCoreOptions {
  armId: string;
  /** The robot profile of the arm behind the board: ids, limits, the keep-out zones. */
  profile: Profile;
  /** `$KMS` through the profile's IK; unset: `$KMS` is refused. */
  kms?: KmsSolver;
  /** The floor and keep-out zones (`zonesKeepOut`) checked before anything is written. */
  keepOut?: KeepOutCheck;
  /** The planner's robot, for motion requests. */
  robot?: MotionRobot;
  /** A beating operator is let go after this long without a `1`, ms (0 = only a `0`). */
  operatorLeaseMs?: number;
}

export class GatewayCore {
  readonly counters = {
    serialChunks: 0,
    statusPayloads: 0,
    frames: 0,
    groups: 0,
    deviceStamps: 0,
    rejected: {} as Record<string, number>,
    controlWritten: 0,
    controlDropped: 0,
    /** `#255PDST!` written because the operator let go or its lease lapsed (the deadman). */
    deadmanStops: 0,
  };
  readonly operator: OperatorWatch;
  /** The controller: every command is checked here before the firmware sees it. */
  readonly controller: ControllerCore;
  /** The control input in front of it: reader, payload bound, rate limit. */
  readonly input: ControlInput;
  private readonly driver: LscDriver;
  private readonly topics;
  private readonly pieces: string[] = [];
  private readonly reader;
  private serialOpen = false;
  private brokerUp = false;
  private o: GatewayCoreOptions;

  constructor(
    options: GatewayCoreOptions,
    private readonly io: GatewayIo,
  ) {
    this.o = options;
    this.topics = armTopics(options.armId);
    const joints = jointsFromProfile(options.profile);
    this.driver = new LscDriver(joints, { write: (text) => this.write(text) });
    ({
      controller: this.controller,
      input: this.input,
      operator: this.operator,
    } = driverControl(joints, this.driver, { kms: options.kms, keepOut: options.keepOut }, io, {
      operatorLeaseMs: options.operatorLeaseMs ?? OPERATOR_LEASE_MS,
      deadmanStopped: (replies) => {
        this.counters.deadmanStops++;
        this.status(replies);
      },
    }));
    this.reader = createReader({
      onFrame: (frame) => {
        // The device's own `$TIM` (if any) is not epoch time we trust: the gateway stamps.
        if (frame.type === 'time') this.counters.deviceStamps++;
        else {
          this.driver.report(frame, this.io.now());
          this.add(frame);
        }
      },
      onGroup: (group) => {
        const inner: string[] = [];
        for (const f of group.frames) {
          this.driver.report(f, this.io.now());
          const text = this.encode(f);
          if (text) inner.push(text);
        }
        if (inner.length === 0) return;
        this.counters.groups++;
        this.pieces.push(`{${inner.join('')}}`);
      },
      onError: (error) => {
        const n = (this.counters.rejected[error.kind] =
          (this.counters.rejected[error.kind] ?? 0) + 1);
        if (n === 1) io.onFirst(`serial:${error.kind}`, `serial input dropped: ${error.message}`);
      },
    });
  }

  private encode(frame: Frame): string {
    try {
      this.counters.frames++;
      const { time: _time, ...bare } = frame;
      return encodeFrame(bare as Frame);
    } catch {
      return '';
    }
  }

  private add(frame: Frame): void {
    const text = this.encode(frame);
    if (text) this.pieces.push(text);
  }

  /** A chunk from the serial line: everything it completes goes out as one payload. */
  fromSerial(chunk: Buffer): void {
    this.counters.serialChunks++;
    this.reader.feed(chunk);
    if (this.pieces.length === 0) return;
    const payload = encodeTime(Math.round(this.io.now())) + this.pieces.join('');
    this.pieces.length = 0;
    this.counters.statusPayloads++;
    this.io.publish(this.topics.status, payload, { qos: 0, retain: false });
  }

  /**
   * The deadman: a `0` on `arm/{id}/operator` — the operator let go or its last will fired, or
   * no operator holds the arm when the gateway (re)connects — or a beating operator's lease
   * running out writes `#255PDST!` to the firmware while the arm moves (./lsc-driver.ts).
   */
  fromOperator(payload: Buffer): void {
    this.operator.receive(payload);
  }

  /** A control payload: checked by the controller core; its replies go out on status. */
  fromControl(payload: Buffer | string): void {
    const replies = this.input.receive(payload, this.io.now());
    if (replies.length) this.status(replies);
  }

  /** The planner's robot now (motion requests), when one was given. */
  get robot(): MotionRobot | undefined {
    return this.o.robot;
  }

  /**
   * A new profile file of the same servos (limits, zones): in force at once. Returns an error,
   * changing nothing, when the servos differ.
   */
  reconfigure(
    profile: Profile,
    kms?: KmsSolver,
    keepOut?: KeepOutCheck,
    robot?: MotionRobot,
  ): string {
    const joints = jointsFromProfile(profile);
    const ids = (js: readonly { id: number }[]) => js.map((j) => j.id).join(' ');
    if (ids(joints) !== ids(this.controller.joints))
      return `profile ${profile.name} drives servos ${ids(joints)}, not ${ids(this.controller.joints)}: restart the gateway`;
    this.o = { ...this.o, profile, kms, keepOut, robot: robot ?? this.o.robot };
    this.driver.setJoints(joints);
    this.controller.reconfigure(joints, { kms, keepOut });
    return '';
  }

  /** Publishes frames (already encoded) as one `$TIM`-stamped status payload. */
  status(frames: string[]): void {
    const payload = encodeTime(Math.round(this.io.now())) + frames.join('');
    this.io.publish(this.topics.status, payload, { qos: 0, retain: false });
  }

  /** Frames the core let through, to the firmware; false when the line is down. */
  private write(text: string): boolean {
    if (this.io.write(Buffer.from(text))) {
      this.counters.controlWritten++;
      return true;
    }
    if (this.counters.controlDropped++ === 0)
      this.io.onFirst('control-dropped', 'serial line down: control payloads dropped');
    return false;
  }

  serialOpened(): void {
    this.reader.reset();
    this.serialOpen = true;
    this.driver.lineOpen(true);
    this.presence();
  }

  serialClosed(): void {
    this.reader.reset();
    this.serialOpen = false;
    this.driver.lineOpen(false);
    this.presence();
  }

  brokerConnected(connected: boolean): void {
    this.brokerUp = connected;
    if (connected) this.presence();
  }

  private presence(): void {
    if (!this.brokerUp) return;
    this.io.publish(this.topics.online, this.serialOpen ? '1' : '0', { qos: 1, retain: true });
  }
}
