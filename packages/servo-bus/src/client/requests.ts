/**
 * The bus client's requests as data: the instruction to send and, when servos answer, which
 * ones, how many bytes, and how their status packets become a typed result. Pure; the client
 * (`./bus-client.ts`) sends them one at a time and collects the answers.
 */
import { decodeField, encodeField } from '../control-table.ts';
import { DYNAMIXEL_MODELS } from '../dynamixel/control-table.ts';
import { FEETECH_MODELS } from '../feetech/control-table.ts';
import type { Instruction } from '../instructions.ts';
import type { StatusPacket } from '../packet.ts';
import type { BusProtocol } from '../protocols.ts';
import { statusProblems } from '../status-errors.ts';
import { degreesToTicks, ticksToDegrees, type Calibration } from '../units.ts';
import { BUS_LAYOUTS, span } from './layout.ts';
import type { BusResult, ReplyStatus, ServoHealth, ServoPosition } from './results.ts';

export interface AwaitedReplies {
  kind: BusResult['kind'];
  /** Servos whose replies are awaited, in the order they come. */
  ids: number[];
  /** Parameter bytes in each reply. */
  replyParams: number;
  /** The result from the replies that came (servos without one are missing). */
  finish(replies: ReadonlyMap<number, StatusPacket>): BusResult;
}

export interface BusRequest {
  instruction: Instruction;
  /** Absent when no answer comes (sync writes). */
  replies?: AwaitedReplies;
}

export interface RequestContext {
  protocol: BusProtocol;
  /** A servo's calibration; throws for a servo the client does not know. */
  calibration(id: number): Calibration;
}

export interface GoalCommand {
  id: number;
  degrees: number;
}

const replyStatus = (protocol: BusProtocol, p: StatusPacket): ReplyStatus => ({
  error: p.error,
  problems: statusProblems(protocol, p.error),
});

/** One servo's answer to PING, READ or WRITE. */
function single(
  ctx: RequestContext,
  instruction: Instruction & { id: number },
  kind: 'ping' | 'model' | 'read' | 'write',
  replyParams: number,
  found: (p: StatusPacket) => Partial<Extract<BusResult, { kind: typeof kind }>>,
): BusRequest {
  const id = instruction.id;
  return {
    instruction,
    replies: {
      kind,
      ids: [id],
      replyParams,
      finish(replies) {
        const p = replies.get(id);
        if (!p) return { kind, id, found: false } as BusResult;
        return {
          kind,
          id,
          found: true,
          status: replyStatus(ctx.protocol, p),
          ...found(p),
        } as BusResult;
      },
    },
  };
}

/** A SYNC READ of `length` bytes at `address`; a reply too short counts as missing. */
function syncRead<T>(
  kind: 'positions' | 'health',
  ids: number[],
  address: number,
  length: number,
  each: (id: number, p: StatusPacket) => T,
): BusRequest {
  return {
    instruction: { op: 'sync-read', address, length, ids },
    replies: {
      kind,
      ids,
      replyParams: length,
      finish(replies) {
        const servos: T[] = [];
        const missing: number[] = [];
        for (const id of ids) {
          const p = replies.get(id);
          if (p && p.params.length >= length) servos.push(each(id, p));
          else missing.push(id);
        }
        return { kind, servos, missing } as BusResult;
      },
    },
  };
}

export const pingRequest = (ctx: RequestContext, id: number): BusRequest =>
  single(ctx, { op: 'ping', id }, 'ping', ctx.protocol === 'dynamixel' ? 3 : 0, (p) =>
    p.params.length >= 3
      ? { modelNumber: p.params[0]! | (p.params[1]! << 8), firmware: p.params[2]! }
      : {},
  );

export function readModelRequest(ctx: RequestContext, id: number): BusRequest {
  const f = BUS_LAYOUTS[ctx.protocol].modelNumber;
  const models = ctx.protocol === 'dynamixel' ? DYNAMIXEL_MODELS : FEETECH_MODELS;
  return single(
    ctx,
    { op: 'read', id, address: f.address, length: f.size },
    'model',
    f.size,
    (p) => {
      if (p.params.length < f.size) return {};
      const modelNumber = decodeField(f, p.params);
      const model = models.find((m) => m.modelNumber === modelNumber);
      return { modelNumber, ...(model ? { modelName: model.name } : {}) };
    },
  );
}

export const readRequest = (ctx: RequestContext, id: number, address: number, length: number) =>
  single(ctx, { op: 'read', id, address, length }, 'read', length, (p) => ({ data: p.params }));

export const writeRequest = (ctx: RequestContext, id: number, address: number, data: Uint8Array) =>
  single(ctx, { op: 'write', id, address, data }, 'write', 0, () => ({}));

export function readPositionsRequest(ctx: RequestContext, ids: number[]): BusRequest {
  const f = BUS_LAYOUTS[ctx.protocol].presentPosition;
  return syncRead<ServoPosition>('positions', ids, f.address, f.size, (id, p) => {
    const ticks = decodeField(f, p.params);
    const degrees = ticksToDegrees(ticks, ctx.calibration(id));
    return { id, ticks, degrees, status: replyStatus(ctx.protocol, p) };
  });
}

export function readHealthRequest(ctx: RequestContext, ids: number[]): BusRequest {
  const layout = BUS_LAYOUTS[ctx.protocol];
  const v = layout.presentVoltage;
  const t = layout.presentTemperature;
  const { address, length } = span(v, t);
  return syncRead<ServoHealth>('health', ids, address, length, (id, p) => ({
    id,
    voltageV:
      Math.round(decodeField(v, p.params, v.address - address) * layout.voltageUnitV * 1000) / 1000,
    temperatureC: decodeField(t, p.params, t.address - address),
    status: replyStatus(ctx.protocol, p),
  }));
}

/** Goals in degrees; with a speed, one sync write of goal and speed together. */
export function writeGoalsRequest(
  ctx: RequestContext,
  goals: GoalCommand[],
  speedDegPerS?: number,
): BusRequest {
  const layout = BUS_LAYOUTS[ctx.protocol];
  const g = layout.goalPosition;
  const ticks = goals.map((goal) =>
    encodeField(g, degreesToTicks(goal.degrees, ctx.calibration(goal.id)), `servo ${goal.id} goal`),
  );
  if (speedDegPerS === undefined) {
    const writes = goals.map((goal, k) => ({ id: goal.id, data: ticks[k]! }));
    return { instruction: { op: 'sync-write', address: g.address, length: g.size, writes } };
  }
  const s = layout.goalSpeed;
  const { address, length } = span(g, s);
  const writes = goals.map((goal, k) => {
    const data = new Uint8Array(length);
    data.set(ticks[k]!, g.address - address);
    const perTurn = ctx.calibration(goal.id).ticksPerTurn;
    const units = Math.max(1, Math.round(layout.speedUnits(Math.abs(speedDegPerS), perTurn)));
    data.set(encodeField(s, units, `servo ${goal.id} speed`), s.address - address);
    return { id: goal.id, data };
  });
  return { instruction: { op: 'sync-write', address, length, writes } };
}

export function setTorqueRequest(ctx: RequestContext, on: boolean, ids: number[]): BusRequest {
  const f = BUS_LAYOUTS[ctx.protocol].torqueEnable;
  const writes = ids.map((id) => ({ id, data: Uint8Array.of(on ? 1 : 0) }));
  return { instruction: { op: 'sync-write', address: f.address, length: f.size, writes } };
}
