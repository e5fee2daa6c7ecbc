/**
 * The host's side of a servo bus, pure: each request method returns the bytes to write and,
 * when the servos answer, remembers what it waits for; `feed()` takes the bytes that came back
 * and returns the typed result once the answer is whole; `expire()` ends the wait when the
 * caller's timer runs out (`replyTimeoutMs`). One request at a time, as a half-duplex bus
 * allows. Degrees ↔ ticks go through each servo's zero and direction.
 */
import { DIALECTS } from '../dialect.ts';
import {
  BusError,
  emptyPacketErrorCounts,
  type PacketError,
  type PacketErrorKind,
} from '../errors.ts';
import { encodeInstruction } from '../instructions.ts';
import type { StatusPacket } from '../packet.ts';
import type { BusProtocol } from '../protocols.ts';
import { fullCalibration, type Calibration, type ServoCalibration } from '../units.ts';
import {
  pingRequest,
  readHealthRequest,
  readModelRequest,
  readPositionsRequest,
  readRequest,
  setTorqueRequest,
  writeGoalsRequest,
  writeRequest,
  type AwaitedReplies,
  type BusRequest,
  type GoalCommand,
  type RequestContext,
} from './requests.ts';
import type { BusResult } from './results.ts';

export interface BusClientOptions {
  protocol: BusProtocol;
  /** The servos on the bus and how their ticks map to joint degrees. */
  servos: ServoCalibration[];
  /** Longest reply accepted. */
  maxPacketLength?: number;
  /** Dropped input from the line (also counted in `counters.errors`). */
  onError?: (error: PacketError) => void;
}

export const DEFAULT_BUS_CLIENT_OPTIONS = {
  /** Added to an answer's transfer time by `replyTimeoutMs`: return delay, USB latency. */
  replyMarginMs: 40,
} as const;

export interface PendingRequest {
  kind: BusResult['kind'];
  /** Servos whose replies are awaited, in the order they come. */
  ids: number[];
  /** Bytes the whole answer takes on the wire. */
  expectedReplyBytes: number;
}

export interface BusClientCounters {
  requests: number;
  results: number;
  /** Waits ended by `expire()` with servos missing. */
  expired: number;
  /** Status packets nobody waited for (late, or from a servo not asked). */
  unexpected: number;
  errors: Record<PacketErrorKind, number>;
}

export interface BusClient {
  readonly protocol: BusProtocol;
  /** What the client waits for, if anything. */
  readonly pending: PendingRequest | undefined;
  /** PING one servo (Dynamixel answers with its model number). */
  ping(id: number): Uint8Array;
  /** READ the model number. */
  readModel(id: number): Uint8Array;
  /** SYNC READ of present positions (all servos by default). */
  readPositions(ids?: number[]): Uint8Array;
  /** SYNC READ of input voltage and temperature (all servos by default). */
  readHealth(ids?: number[]): Uint8Array;
  /** READ raw bytes. */
  read(id: number, address: number, length: number): Uint8Array;
  /** WRITE raw bytes, acknowledged. */
  write(id: number, address: number, data: Uint8Array): Uint8Array;
  /** SYNC WRITE of goals, with a speed (°/s) when given (else the last one stays); no answer. */
  writeGoals(goals: GoalCommand[], options?: { speedDegPerS?: number }): Uint8Array;
  /** SYNC WRITE of Torque Enable (all servos by default); no answer comes. */
  setTorque(on: boolean, ids?: number[]): Uint8Array;
  /** Bytes from the line; returns the result completed by them, if any. */
  feed(chunk: Uint8Array): BusResult[];
  /** The wait is over: the result with what arrived (missing servos listed), if one was pending. */
  expire(): BusResult | undefined;
  /** A servo's calibration, defaults filled in. */
  calibration(id: number): Calibration;
  readonly counters: BusClientCounters;
}

/** Time to allow for an answer of `bytes` bytes at `baudRate` (10 bits a byte), plus a margin. */
export const replyTimeoutMs = (
  bytes: number,
  baudRate: number,
  marginMs: number = DEFAULT_BUS_CLIENT_OPTIONS.replyMarginMs,
): number => (bytes * 10 * 1000) / baudRate + marginMs;

interface Waiting extends AwaitedReplies {
  replies: Map<number, StatusPacket>;
  expectedReplyBytes: number;
}

export function createBusClient(options: BusClientOptions): BusClient {
  const { protocol } = options;
  const calibrations = new Map(options.servos.map((s) => [s.id, fullCalibration(s)]));
  const allIds = options.servos.map((s) => s.id);
  const counters: BusClientCounters = {
    requests: 0,
    results: 0,
    expired: 0,
    unexpected: 0,
    errors: emptyPacketErrorCounts(),
  };
  /** Bytes of a status packet with `params` parameter bytes (before any Dynamixel stuffing). */
  const statusBytes = (params: number) => (protocol === 'dynamixel' ? 11 : 6) + params;
  let waiting: Waiting | undefined;
  let completed: BusResult[] = [];

  const ctx: RequestContext = {
    protocol,
    calibration(id) {
      const c = calibrations.get(id);
      if (!c) throw new BusError('unknown-servo', `servo ${id} is not on this bus client`);
      return c;
    },
  };

  function send(request: BusRequest): Uint8Array {
    if (waiting) throw new BusError('busy', `still waiting for the answer to ${waiting.kind}`);
    const bytes = encodeInstruction(protocol, request.instruction);
    counters.requests++;
    const r = request.replies;
    if (r)
      waiting = {
        ...r,
        replies: new Map(),
        expectedReplyBytes: r.ids.length * statusBytes(r.replyParams),
      };
    return bytes;
  }

  function finish() {
    const w = waiting!;
    waiting = undefined;
    counters.results++;
    completed.push(w.finish(w.replies));
  }

  function onStatus(p: StatusPacket) {
    const w = waiting;
    if (!w || !w.ids.includes(p.id) || w.replies.has(p.id)) {
      counters.unexpected++;
      return;
    }
    w.replies.set(p.id, p);
    if (w.replies.size === w.ids.length) finish();
  }

  const reader = DIALECTS[protocol].createReader({
    direction: 'status',
    ...(options.maxPacketLength === undefined ? {} : { maxPacketLength: options.maxPacketLength }),
    // An instruction read here is our own, echoed by a half-duplex adapter.
    onPacket: (p) => (p.type === 'status' ? onStatus(p) : undefined),
    onError(e) {
      counters.errors[e.kind]++;
      options.onError?.(e);
    },
  });

  return {
    protocol,
    get pending() {
      if (!waiting) return undefined;
      return {
        kind: waiting.kind,
        ids: [...waiting.ids],
        expectedReplyBytes: waiting.expectedReplyBytes,
      };
    },
    calibration: ctx.calibration,
    counters,
    ping: (id) => send(pingRequest(ctx, id)),
    readModel: (id) => send(readModelRequest(ctx, id)),
    readPositions: (ids = allIds) => send(readPositionsRequest(ctx, ids)),
    readHealth: (ids = allIds) => send(readHealthRequest(ctx, ids)),
    read: (id, address, length) => send(readRequest(ctx, id, address, length)),
    write: (id, address, data) => send(writeRequest(ctx, id, address, data)),
    writeGoals: (goals, opts = {}) => send(writeGoalsRequest(ctx, goals, opts.speedDegPerS)),
    setTorque: (on, ids = allIds) => send(setTorqueRequest(ctx, on, ids)),

    feed(chunk) {
      reader.feed(chunk);
      const out = completed;
      completed = [];
      return out;
    },

    expire() {
      if (!waiting) return undefined;
      // The end of the wait is the end of a stream: a reply held behind a false header is read now.
      reader.flush();
      if (waiting) {
        counters.expired++;
        finish();
      }
      const result = completed.pop();
      completed = [];
      return result;
    },
  };
}
