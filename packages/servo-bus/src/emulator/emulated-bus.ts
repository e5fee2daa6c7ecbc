/**
 * An emulated servo bus: the bytes a host writes go in, the bytes the servos would answer
 * come out, as on a real half-duplex line. Only the addressed servo answers; SYNC READ is
 * answered by each listed servo in the order listed; broadcasts (id 254) other than PING and
 * SYNC READ get no answer, as on real buses. Time is the caller's: `advance(nowMs)` turns the
 * shafts toward their goals. No timers, no I/O: the simulator (or a test) owns the serial port
 * and the clock.
 */
import { DIALECTS } from '../dialect.ts';
import type { ServoModel } from '../control-table.ts';
import { DYNAMIXEL_MODELS, XM430_W350, type XSeriesField } from '../dynamixel/control-table.ts';
import { BusError, emptyPacketErrorCounts, type PacketErrorKind } from '../errors.ts';
import { FEETECH_MODELS, STS3215, type StsField } from '../feetech/control-table.ts';
import { decodeInstruction } from '../instructions.ts';
import type { Packet, PacketReader, StatusPacket } from '../packet.ts';
import { BROADCAST_ID, MAX_SERVO_ID, type BusProtocol } from '../protocols.ts';
import { dynamixelErrorByte } from '../status-errors.ts';
import { DynamixelServo } from './dynamixel-servo.ts';
import { FeetechServo } from './feetech-servo.ts';
import type { BusServo, EmulatedServo } from './servo-base.ts';

export interface EmulatedServoSpec {
  id: number;
  /** A model's name (`XM430-W350`, `XL430-W250`, `STS3215`) or description; default per protocol. */
  model?: string | ServoModel;
  /** Present position at power-on, ticks. */
  position?: number;
  /** Temperature at power-on, °C (default: the model's). */
  temperatureC?: number;
  /** Input voltage at power-on, V (default: the model's). */
  voltageV?: number;
}

export interface EmulatedBusOptions {
  protocol: BusProtocol;
  servos: EmulatedServoSpec[];
  /** The clock at power-on, ms: the first `advance(nowMs)` moves the shafts from here. */
  startMs?: number;
  /** Longest instruction packet read from the line. */
  maxPacketLength?: number;
}

export const DEFAULT_EMULATED_BUS_OPTIONS = {
  startMs: 0,
  position: 2048,
  models: { dynamixel: XM430_W350, feetech: STS3215 } as Record<BusProtocol, ServoModel>,
} as const;

export interface EmulatedBusCounters {
  /** Instruction packets read. */
  instructions: number;
  /** Status packets written. */
  replies: number;
  /** Instructions this bus does not know, or with parameters that do not parse. */
  refused: number;
  /** Packets for ids nobody here has, and status packets (another host's echo). */
  ignored: number;
  /** Input the reader dropped, per kind. */
  errors: Record<PacketErrorKind, number>;
}

export interface EmulatedBus {
  readonly protocol: BusProtocol;
  readonly servos: readonly EmulatedServo[];
  /** The servo answering to `id` now, if any. */
  servo(id: number): EmulatedServo | undefined;
  /** Bytes from the host in; the servos' answers to every instruction completed by them out. */
  feed(bytes: Uint8Array): Uint8Array;
  /** Turns the shafts toward their goals up to `nowMs` (non-decreasing; earlier times are ignored). */
  advance(nowMs: number): void;
  readonly counters: EmulatedBusCounters;
}

function findModel(protocol: BusProtocol, model: string | ServoModel | undefined): ServoModel {
  if (model === undefined) return DEFAULT_EMULATED_BUS_OPTIONS.models[protocol];
  const found =
    typeof model === 'string'
      ? [...DYNAMIXEL_MODELS, ...FEETECH_MODELS].find(
          (m) => m.name.toUpperCase() === model.toUpperCase(),
        )
      : model;
  if (!found) throw new BusError('unsupported', `unknown servo model "${String(model)}"`);
  if (found.protocol !== protocol)
    throw new BusError(
      'unsupported',
      `${found.name} is a ${found.protocol} servo, not ${protocol}`,
    );
  return found;
}

function makeServo(protocol: BusProtocol, spec: EmulatedServoSpec): BusServo {
  if (!Number.isInteger(spec.id) || spec.id < 0 || spec.id > MAX_SERVO_ID[protocol])
    throw new BusError('out-of-range', `servo id ${spec.id} is not 0…${MAX_SERVO_ID[protocol]}`);
  const model = findModel(protocol, spec.model);
  const position = spec.position ?? DEFAULT_EMULATED_BUS_OPTIONS.position;
  const servo =
    protocol === 'dynamixel'
      ? new DynamixelServo(model as ServoModel<XSeriesField>, spec.id, position)
      : new FeetechServo(model as ServoModel<StsField>, spec.id, position);
  if (spec.temperatureC !== undefined) servo.setTemperature(spec.temperatureC);
  if (spec.voltageV !== undefined) servo.setVoltage(spec.voltageV);
  return servo;
}

export function createEmulatedBus(options: EmulatedBusOptions): EmulatedBus {
  const { protocol } = options;
  const dialect = DIALECTS[protocol];
  const servos = options.servos.map((spec) => makeServo(protocol, spec));
  const ids = new Set(servos.map((s) => s.id));
  if (ids.size !== servos.length) throw new BusError('out-of-range', 'two servos with the same id');
  let lastMs = options.startMs ?? DEFAULT_EMULATED_BUS_OPTIONS.startMs;
  const counters: EmulatedBusCounters = {
    instructions: 0,
    replies: 0,
    refused: 0,
    ignored: 0,
    errors: emptyPacketErrorCounts(),
  };
  let out: Uint8Array[] = [];

  const byId = (id: number) => servos.find((s) => s.id === id);
  const send = (status: StatusPacket | null) => {
    if (!status) return;
    out.push(dialect.encode(status));
    counters.replies++;
  };

  function onPacket(packet: Packet) {
    if (packet.type === 'status') {
      counters.ignored++;
      return;
    }
    counters.instructions++;
    const broadcast = packet.id === BROADCAST_ID;
    const target = broadcast ? undefined : byId(packet.id);
    if (!broadcast && !target) {
      counters.ignored++;
      return;
    }
    const decoded = decodeInstruction(protocol, packet);
    if (!decoded.ok) {
      counters.refused++;
      // Dynamixel answers an instruction it cannot run with an Instruction Error; Feetech stays silent.
      if (target && protocol === 'dynamixel')
        send({
          type: 'status',
          id: target.id,
          error: dynamixelErrorByte(
            decoded.reason === 'unknown-instruction' ? 'instruction' : 'data-length',
            false,
          ),
          params: new Uint8Array(0),
        });
      return;
    }
    const ins = decoded.instruction;
    switch (ins.op) {
      case 'sync-read':
        for (const id of ins.ids)
          send(
            byId(id)?.handle({ op: 'read', id, address: ins.address, length: ins.length }, false) ??
              null,
          );
        return;
      case 'sync-write':
        for (const w of ins.writes)
          byId(w.id)?.handle({ op: 'write', id: w.id, address: ins.address, data: w.data }, true);
        return;
      case 'ping':
      case 'read':
      case 'write':
      case 'reg-write':
      case 'action':
      case 'reboot':
        if (target) send(target.handle(ins, false));
        else for (const s of [...servos].sort((a, b) => a.id - b.id)) send(s.handle(ins, true));
        return;
      default: {
        const never: never = ins;
        throw new Error(`unhandled instruction ${String(never)}`);
      }
    }
  }

  const reader: PacketReader = dialect.createReader({
    direction: 'instruction',
    ...(options.maxPacketLength === undefined ? {} : { maxPacketLength: options.maxPacketLength }),
    onPacket,
    onError(error) {
      counters.errors[error.kind]++;
      // A Dynamixel servo answers a packet for it whose CRC fails with a CRC error.
      if (error.kind === 'bad-checksum' && protocol === 'dynamixel' && error.bytes.length > 4)
        send(byId(error.bytes[4]!)?.checksumError() ?? null);
    },
  });

  return {
    protocol,
    servos,
    servo: byId,
    feed(bytes) {
      reader.feed(bytes);
      const replies = out;
      out = [];
      if (replies.length === 1) return replies[0]!;
      const all = new Uint8Array(replies.reduce((n, r) => n + r.length, 0));
      let at = 0;
      for (const r of replies) {
        all.set(r, at);
        at += r.length;
      }
      return all;
    },
    advance(nowMs) {
      if (!(nowMs > lastMs)) return;
      const dt = nowMs - lastMs;
      lastMs = nowMs;
      for (const s of servos) s.advance(dt);
    },
    counters,
  };
}
