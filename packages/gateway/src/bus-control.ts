/**
 * Control frames on a servo bus (pure): what the seed firmware answered, the bus gateway
 * answers. Pulse and angle moves become goals with their limits checked (a group is all or
 * nothing) and `T…` turned into a speed; `#IIIPDST!` / `#255PDST!` hold position now and drop
 * queued goals; `#IIIPRAD!` / `#IIIPRTV!` are answered from the last reads; `$PNG` is echoed.
 * `$KMS` goes through the profile's IK (`./bus-kms.ts`) when one is given, answered `$KMS:c!`
 * and moved only with 0. Refusals are `$ERR` replies. Goals that would put the tool or a joint
 * below the floor are refused (`$ERR:floor …`, `$KMS:1!`), and moves whose path enters a keep-out
 * zone (`$ERR:zone …`, `$KMS:25!`), as the simulator refuses them.
 */
import {
  createReader,
  encodeAngle,
  encodeControllerError,
  encodeHealth,
  encodeKmsResult,
  encodePing,
  SERVO_ID_ALL,
  type Frame,
} from '@armtwin/protocol';
import {
  KMS_FLOOR_CODE,
  KMS_LIMIT_CODE,
  KMS_ZONE_CODE,
  type BusKeepOut,
  type BusKmsSolver,
} from './bus-kms.ts';
import { keepOutKind } from '@armtwin/motion';
import {
  angleGoal,
  goalFor,
  pulseGoal,
  type BusGoal,
  type BusJoint,
  type GoalResult,
} from './bus-servos.ts';

/** What the control side needs of the gateway core. */
export interface BusControlTarget {
  readonly ready: boolean;
  readonly positions: ReadonlyMap<number, number>;
  readonly health: ReadonlyMap<number, { temp: number; mv: number }>;
  readonly found: ReadonlySet<number>;
  writeGoals(goals: BusGoal[]): void;
  hold(ids: number[]): void;
}

export const KMS_REPLY = 'kms: no IK for this profile';
export const NOT_READY_REPLY = 'gateway: serial line down';

export class BusControl {
  readonly counters = {
    frames: 0,
    refused: {} as Record<string, number>,
  };
  private replies: string[] = [];
  private readonly reader;

  constructor(
    private readonly target: BusControlTarget,
    private readonly joints: readonly BusJoint[],
    private readonly kmsSolver?: BusKmsSolver,
    private readonly keepOut?: BusKeepOut,
  ) {
    this.reader = createReader({
      onFrame: (f) => this.frame(f),
      onGroup: (g) => {
        const moves = g.frames.filter((f) => f.type === 'move' || f.type === 'angleMove');
        if (moves.length === g.frames.length && moves.length > 0) return this.moves(moves);
        for (const f of g.frames) this.frame(f);
      },
      onError: (e) => this.refuse(e.kind, e.message),
    });
  }

  /** A control payload in; the reply frames (encoded) out. */
  receive(payload: Uint8Array | string): string[] {
    this.reader.feed(payload);
    const out = this.replies;
    this.replies = [];
    return out;
  }

  /** Moves refused by a keep-out rule so far, and why the last one was (for the audit record). */
  keepOutRefusals = { count: 0, last: '' };

  private refuse(kind: string, text: string): void {
    this.counters.refused[kind] = (this.counters.refused[kind] ?? 0) + 1;
    this.replies.push(encodeControllerError(text));
  }

  private ids(id: number): number[] {
    return id === SERVO_ID_ALL ? this.joints.map((j) => j.id) : [id];
  }

  private frame(f: Frame): void {
    this.counters.frames++;
    switch (f.type) {
      case 'move':
      case 'angleMove':
        return this.moves([f]);
      case 'stop':
        if (!this.target.ready) return this.refuse('not-ready', NOT_READY_REPLY);
        return this.target.hold(this.ids(f.id));
      case 'readPosition':
        for (const id of this.ids(f.id)) {
          const deg = this.target.positions.get(id);
          if (deg === undefined || !this.target.found.has(id))
            this.refuse('no-reading', `servo ${String(id).padStart(3, '0')} not answering`);
          else this.replies.push(encodeAngle(id, deg));
        }
        return;
      case 'readHealth':
        for (const id of this.ids(f.id)) {
          const h = this.target.health.get(id);
          if (!h || !this.target.found.has(id))
            this.refuse('no-reading', `servo ${String(id).padStart(3, '0')} not answering`);
          else this.replies.push(encodeHealth(id, h.temp, h.mv));
        }
        return;
      case 'ping':
        this.replies.push(encodePing(f.seq));
        return;
      case 'kms':
        return this.kms(f.x, f.y, f.z, f.alpha, f.ms);
      case 'position':
      case 'angle':
      case 'health':
      case 'kmsResult':
      case 'time':
      case 'controllerError':
        return this.refuse('unexpected', `unexpected ${f.type} frame`);
      default: {
        const never: never = f;
        throw new Error(`unhandled frame ${String(never)}`);
      }
    }
  }

  /** `$KMS:x,y,z[,a],t!`: every servo the IK gives an angle moves, together, over `t` ms. */
  private kms(x: number, y: number, z: number, alpha: number | undefined, ms: number): void {
    if (!this.kmsSolver) return this.refuse('kms', KMS_REPLY);
    if (!this.target.ready) return this.refuse('not-ready', NOT_READY_REPLY);
    const now = this.positionsNow();
    const r = this.kmsSolver(x, y, z, alpha, now);
    const goals: BusGoal[] = [];
    let code = r.code;
    if (code === 0)
      r.degrees.forEach((deg, i) => {
        if (Number.isNaN(deg)) return;
        const g = goalFor(this.joints[i]!, deg, ms, now[i]!, `A${deg.toFixed(2)}`);
        if (g.ok) goals.push(g.goal);
        else code = KMS_LIMIT_CODE;
      });
    const keepOut = code === 0 ? this.floorReason(now, goals) : '';
    if (keepOut) {
      const kind = keepOutKind(keepOut);
      code = kind === 'zone' ? KMS_ZONE_CODE : KMS_FLOOR_CODE;
      this.counters.refused[kind] = (this.counters.refused[kind] ?? 0) + 1;
    }
    this.replies.push(encodeKmsResult(code));
    if (code === 0 && goals.length) this.target.writeGoals(goals);
    else this.counters.refused.kms = (this.counters.refused.kms ?? 0) + 1;
  }

  /** Moves that start together: every one valid, or none is made. */
  private moves(frames: Frame[]): void {
    if (!this.target.ready) return this.refuse('not-ready', NOT_READY_REPLY);
    const goals: BusGoal[] = [];
    for (const f of frames) {
      if (f.type !== 'move' && f.type !== 'angleMove') continue;
      for (const id of this.ids(f.id)) {
        const joint = this.joints.find((j) => j.id === id);
        if (!joint)
          return this.refuse('unknown-servo', `unknown servo ${String(id).padStart(3, '0')}`);
        const from = this.target.positions.get(id) ?? NaN;
        const r: GoalResult =
          f.type === 'move'
            ? pulseGoal(joint, f.pwm, f.ms, from)
            : angleGoal(joint, f.deg, f.ms, from);
        if (!r.ok) return this.refuse('limit', r.error);
        goals.push(r.goal);
      }
    }
    const floor = this.floorReason(this.positionsNow(), goals);
    if (floor) return this.refuse(keepOutKind(floor), floor);
    if (goals.length) this.target.writeGoals(goals);
  }

  private positionsNow(): number[] {
    return this.joints.map((j) => this.target.positions.get(j.id) ?? NaN);
  }

  /** The keep-out zones for these goals from the positions `now`: the reason, or '' when clear. */
  private floorReason(now: readonly number[], goals: readonly BusGoal[]): string {
    if (!this.keepOut || goals.length === 0) return '';
    const to = [...now];
    for (const g of goals) to[this.joints.findIndex((j) => j.id === g.id)] = g.degrees;
    const reason = this.keepOut(now, to);
    if (reason) this.keepOutRefusals = { count: this.keepOutRefusals.count + 1, last: reason };
    return reason;
  }
}
