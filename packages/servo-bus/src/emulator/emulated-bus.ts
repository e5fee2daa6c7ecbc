/**
 * An emulated servo bus: the bytes a host writes go in, the bytes the servos would answer
 * come out, as on a real half-duplex line. Only the addressed servo answers; SYNC READ is
 * answered by each listed servo in the order listed; broadcasts (id 254) other than PING and
 * SYNC READ get no answer, as on real buses. Time is the caller's: `advance(nowMs)` turns the
 * shafts toward their goals. No timers, no I/O: the simulator (or a test) owns the serial port
 * and the clock.
 *
 * Faults a bus really has can be set up: two servos with one id (`idClash: 'collide'`: both
 * answer at once, one a byte's time after the other, and their bytes mix on the wire as on an
 * open-drain line, a 0 bit from either winning, so the host reads a garbled packet), a servo set to another baud rate than the line's
 * (`setLineBaud`: it hears nothing), any control-table field of a servo (`fields`: a firmware,
 * a 7.4 V servo's voltage limits, an error flag).
 */
import { DIALECTS } from '../dialect.ts';
import type { ServoModel } from '../control-table.ts';
import {
  DYNAMIXEL_BAUD_RATES,
  DYNAMIXEL_MODELS,
  XM430_W350,
  type XSeriesField,
} from '../dynamixel/control-table.ts';
import { BusError, emptyPacketErrorCounts, type PacketErrorKind } from '../errors.ts';
import {
  FEETECH_BAUD_RATES,
  FEETECH_MODELS,
  STS3215,
  type StsField,
} from '../feetech/control-table.ts';
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
  /** Control-table fields set at power-on, by name (`EmulatedServo.setField`). */
  fields?: Record<string, number>;
}

export interface EmulatedBusOptions {
  protocol: BusProtocol;
  servos: EmulatedServoSpec[];
  /** The clock at power-on, ms: the first `advance(nowMs)` moves the shafts from here. */
  startMs?: number;
  /** Longest instruction packet read from the line. */
  maxPacketLength?: number;
  /** Two servos with one id: refused (default), or both on the bus, answering at once. */
  idClash?: 'refuse' | 'collide';
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
  /**
   * The line's baud rate, as the host set it: a servo whose Baud Rate field says another hears
   * nothing. Undefined (the default): every servo hears, whatever its field says.
   */
  setLineBaud(baud: number | undefined): void;
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
  for (const [name, value] of Object.entries(spec.fields ?? {})) servo.setField(name, value);
  return servo;
}

export function createEmulatedBus(options: EmulatedBusOptions): EmulatedBus {
  const { protocol } = options;
  const dialect = DIALECTS[protocol];
  const servos = options.servos.map((spec) => makeServo(protocol, spec));
  const ids = new Set(servos.map((s) => s.id));
  if (ids.size !== servos.length && options.idClash !== 'collide')
    throw new BusError('out-of-range', 'two servos with the same id');
  let lineBaud: number | undefined;
  const bauds = protocol === 'dynamixel' ? DYNAMIXEL_BAUD_RATES : FEETECH_BAUD_RATES;
  const hears = (s: BusServo) => lineBaud === undefined || bauds[s.field('baudRate')] === lineBaud;
  let lastMs = options.startMs ?? DEFAULT_EMULATED_BUS_OPTIONS.startMs;
  const counters: EmulatedBusCounters = {
    instructions: 0,
    replies: 0,
    refused: 0,
    ignored: 0,
    errors: emptyPacketErrorCounts(),
  };
  let out: Uint8Array[] = [];

  const byId = (id: number) => servos.find((s) => s.id === id && hears(s));
  const allById = (id: number) => servos.filter((s) => s.id === id && hears(s));
  const send = (status: StatusPacket | null) => {
    if (!status) return;
    out.push(dialect.encode(status));
    counters.replies++;
  };
  /** Every servo of `id` answers at once: one answer, or their bytes mixed on the wire. */
  const answer = (id: number, reply: (s: BusServo) => StatusPacket | null) => {
    const wire = allById(id)
      .map(reply)
      .filter((r): r is StatusPacket => r !== null)
      .map((r) => dialect.encode(r));
    if (wire.length === 0) return;
    // Servos never answer in step: each one a byte's time after the one before.
    const mixed = new Uint8Array(Math.max(...wire.map((w, k) => w.length + k))).fill(0xff);
    wire.forEach((w, k) => w.forEach((b, i) => (mixed[i + k]! &= b)));
    out.push(mixed);
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
          answer(id, (s) =>
            s.handle({ op: 'read', id, address: ins.address, length: ins.length }, false),
          );
        return;
      case 'sync-write':
        for (const w of ins.writes)
          for (const s of allById(w.id))
            s.handle({ op: 'write', id: w.id, address: ins.address, data: w.data }, true);
        return;
      case 'ping':
      case 'read':
      case 'write':
      case 'reg-write':
      case 'action':
      case 'reboot':
        if (target) answer(target.id, (s) => s.handle(ins, false));
        else
          for (const s of [...servos].filter(hears).sort((a, b) => a.id - b.id))
            send(s.handle(ins, true));
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
    setLineBaud(baud) {
      lineBaud = baud;
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
