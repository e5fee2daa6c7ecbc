/**
 * One arm's MQTT traffic as Foxglove messages (./channels.ts): each status payload that moved a
 * servo gives its joint states (the profile's joints, URDF names and units: ./ros2's
 * JointStateBuilder, the ROS 2 bridge's own) and every URDF link's transform at them
 * (`linkTransforms` of @armtwin/robot, the MCAP export's); each health report a servo's health;
 * each move on a control topic the joints it asked for; each plan the arm tells of
 * (`arm/{id}/feedback`, ./plan-feed.ts) its end pose; each control event (`arm/{id}/audit`),
 * thermal warning (`arm/{id}/alert`) and controller `$ERR` a log line. Messages carry the arm's
 * own `$TIM` stamp (arrival time when a payload has none). Pure: fed topics, payloads and times.
 */
import {
  linkTransforms,
  jointFromPwm,
  jointFromServo,
  type Profile,
  type UrdfJoint,
} from '@armtwin/robot';
import { JointStateBuilder } from '@armtwin/ros2';
import {
  auditTopic,
  createReader,
  parseAudit,
  parseUserTopic,
  temperatureLevel,
  topic,
  voltageLevel,
  worstLevel,
  type Frame,
} from '@armtwin/protocol';
import { parseThermalAlert, thermalAlertTopic } from '@armtwin/thermal';
import { stampOf } from './channels.ts';
import { PLAN_FRAME_PREFIX, type ChannelKind } from './topics.ts';
import { plannedPose } from './plan-feed.ts';

export interface FoxgloveMessage {
  kind: ChannelKind;
  ns: bigint;
  body: object;
}

/** foxglove.LogLevel */
const INFO = 2;
const WARNING = 3;

export interface ArmFeedCounts {
  /** Payloads on the arm's topics that held nothing readable (bad audit, alert, feedback). */
  unreadable: number;
}

export class ArmFeed {
  readonly counts: ArmFeedCounts = { unreadable: 0 };
  private readonly joints: JointStateBuilder;
  private readonly byId: Map<number, Profile['servos'][number]>;
  private readonly status: string;
  private readonly control: string;
  private readonly audit: string;
  private readonly alert: string;
  private readonly feedback: string;
  private out: FoxgloveMessage[] = [];
  private stampMs = 0;
  /** Each servo's last commanded joint value (profile order; NaN: none yet). */
  private readonly commanded: number[];
  /** Each joint's last reported value, by joint name. */
  private readonly reported = new Map<string, number>();
  /** The servos (profile index → ms) the control payload being read moves. */
  private moved = new Map<number, number>();
  private readonly slotById: Map<number, number>;
  private readonly statusReader;
  private readonly controlReader;

  constructor(
    readonly armId: string,
    readonly profile: Profile,
    private readonly urdfJoints: readonly UrdfJoint[],
  ) {
    this.joints = new JointStateBuilder(profile);
    this.byId = new Map(profile.servos.map((s) => [s.id, s]));
    this.slotById = new Map(profile.servos.map((s, i) => [s.id, i]));
    this.commanded = profile.servos.map(() => NaN);
    this.status = topic(armId, 'status');
    this.control = topic(armId, 'control');
    this.audit = auditTopic(armId);
    this.alert = thermalAlertTopic(armId);
    this.feedback = topic(armId, 'feedback');
    const each = (on: (f: Frame) => void) =>
      createReader({ onFrame: on, onGroup: (g) => g.frames.forEach(on) });
    this.statusReader = each((f) => this.onStatusFrame(f));
    this.controlReader = each((f) => this.onControlFrame(f));
  }

  /** The MQTT topics this feed reads that any viewer may read (subscribe to them). */
  get topics(): string[] {
    return [this.status, this.audit, this.alert, this.feedback];
  }

  /** The control topics it reads for the targets (a device's or the middleware's right). */
  get controlTopics(): string[] {
    return [this.control, `${this.control}/+`];
  }

  /** Each servo's latest pulse width (profile order; NaN until it reported). */
  get pwm(): readonly number[] {
    return this.joints.pwm;
  }

  /** The messages one MQTT message gives (`nowMs`: its arrival, for unstamped payloads). */
  feed(t: string, payload: Uint8Array, nowMs: number): FoxgloveMessage[] {
    this.out = [];
    this.stampMs = nowMs;
    if (t === this.status) this.onStatus(payload);
    else if (t === this.control) this.onControl('', payload);
    else if (t === this.audit) this.onAudit(payload);
    else if (t === this.alert) this.onAlert(payload);
    else if (t === this.feedback) this.onFeedback(payload);
    else {
      const u = parseUserTopic(t);
      if (u?.armId === this.armId && u.kind === 'control') this.onControl(u.user, payload);
    }
    return this.out;
  }

  private push(kind: ChannelKind, ms: number, body: (time: object) => object): void {
    const { ns, time } = stampOf(ms);
    this.out.push({ kind, ns, body: body(time) });
  }

  private onStatus(payload: Uint8Array): void {
    const js = this.joints.feed(payload);
    this.statusReader.clearStamp();
    this.statusReader.feed(payload);
    if (!js) return;
    const ms = js.stamp_ms ?? this.stampMs;
    const joints = js.name.map((name, i) => ({ name, position: js.position[i]! }));
    for (const j of joints) this.reported.set(j.name, j.position);
    this.push('joint_states', ms, (timestamp) => ({ timestamp, joints }));
    const values = new Map(joints.map((j) => [j.name, j.position]));
    this.push('tf', ms, (timestamp) => ({ transforms: this.transforms(values, timestamp, '') }));
  }

  /** Every URDF joint's transform at `values`, frames prefixed (a prefixed tree hangs off the root). */
  private transforms(values: Map<string, number>, timestamp: object, prefix: string): object[] {
    const links = linkTransforms(this.urdfJoints, values);
    const out = links.map((t) => ({
      timestamp,
      parent_frame_id: prefix + t.parent,
      child_frame_id: prefix + t.child,
      translation: { x: t.translation[0], y: t.translation[1], z: t.translation[2] },
      rotation: { x: t.rotation[0], y: t.rotation[1], z: t.rotation[2], w: t.rotation[3] },
    }));
    const children = new Set(links.map((t) => t.child));
    const root = links.find((t) => !children.has(t.parent))?.parent;
    if (prefix && root)
      out.unshift({
        timestamp,
        parent_frame_id: root,
        child_frame_id: prefix + root,
        translation: { x: 0, y: 0, z: 0 },
        rotation: { x: 0, y: 0, z: 0, w: 1 },
      });
    return out;
  }

  /** A plan's end pose (./plan-feed.ts): the joints, and the arm drawn there as `plan/…` frames. */
  private onFeedback(payload: Uint8Array): void {
    const p = plannedPose(this.profile, payload, this.reported);
    if (p === 'unreadable') return void this.counts.unreadable++;
    if (!p) return;
    const { joints, t, ...summary } = p;
    const ms = t ?? this.stampMs;
    this.push('plan', ms, (timestamp) => ({ timestamp, ...summary, joints }));
    const values = new Map(
      joints.filter((j) => !Number.isNaN(j.position)).map((j) => [j.name, j.position]),
    );
    this.push('plan_tf', ms, (timestamp) => ({
      transforms: this.transforms(values, timestamp, PLAN_FRAME_PREFIX),
    }));
  }

  private onStatusFrame(f: Frame): void {
    const ms = f.time ?? this.stampMs;
    if (f.type === 'health') {
      const servo = this.byId.get(f.id);
      const volt = f.mv / 1000;
      this.push('health', ms, (timestamp) => ({
        timestamp,
        id: String(f.id).padStart(3, '0'),
        joint: servo?.joint ?? '',
        temp: f.temp,
        volt,
        level: worstLevel(temperatureLevel(f.temp), voltageLevel(volt)),
      }));
    } else if (f.type === 'controllerError')
      this.log(ms, WARNING, `${this.armId}/controller`, f.text);
  }

  /**
   * Every joint, in servo order, as the arm was last sent (the MCAP export's `/{arm}/targets`
   * too, so a plot by index reads both): a joint this command moves carries its `ms`, one it
   * leaves holds its last target, or where it was last reported (`ms` 0).
   */
  private onControl(by: string, payload: Uint8Array): void {
    this.moved = new Map();
    this.controlReader.clearStamp();
    this.controlReader.feed(payload);
    if (this.moved.size === 0) return;
    const joints = this.profile.servos.map((s, i) => {
      const target = this.commanded[i]!;
      const position = Number.isNaN(target) ? (this.reported.get(s.joint) ?? NaN) : target;
      return { name: s.joint, position, ms: this.moved.get(i) ?? 0 };
    });
    this.push('targets', this.stampMs, (timestamp) => ({ timestamp, by, joints }));
  }

  private onControlFrame(f: Frame): void {
    if (f.type !== 'move' && f.type !== 'angleMove') return;
    const servo = this.byId.get(f.id);
    const i = this.slotById.get(f.id);
    if (!servo || i === undefined) return;
    this.commanded[i] =
      f.type === 'move' ? jointFromPwm(servo, f.pwm) : jointFromServo(servo, f.deg);
    this.moved.set(i, f.ms);
  }

  private onAudit(payload: Uint8Array): void {
    const e = parseAudit(payload);
    if (!e) return void this.counts.unreadable++;
    const level = e.kind.startsWith('refused') || e.kind === 'e-stop' ? WARNING : INFO;
    this.log(e.at, level, `${this.armId}/control`, `${e.kind}: ${e.detail}`);
  }

  private onAlert(payload: Uint8Array): void {
    const a = parseThermalAlert(payload);
    if (!a) return void this.counts.unreadable++;
    this.log(
      a.at,
      a.kind === 'thermal-warning' ? WARNING : INFO,
      `${this.armId}/thermal`,
      a.detail,
    );
  }

  private log(ms: number, level: number, name: string, message: string): void {
    this.push('log', ms, (timestamp) => ({ timestamp, level, message, name, file: '', line: 0 }));
  }
}
