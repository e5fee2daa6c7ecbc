/**
 * The servo doctor's scan: which servos answer, at which baud rate, and what each says of
 * itself (model, firmware, voltage limits and the supply it measures, temperature, error
 * flags, homing offset and position). The line is the caller's (`DoctorLink`: a serial port,
 * or the emulated bus in a test); requests and replies go through the bus client, so the
 * bytes are the gateway's own. A reply that arrives garbled (a bad checksum, a broken packet:
 * LeRobot's "Incorrect status packet") is recorded as such for the id it answered.
 */
import { decodeField, type Field } from '../control-table.ts';
import { X_SERIES_TABLE } from '../dynamixel/control-table.ts';
import { STS_TABLE, FEETECH_VOLTAGE_UNIT_V } from '../feetech/control-table.ts';
import { createBusClient, replyTimeoutMs, type BusClient } from '../client/bus-client.ts';
import type { BusResult } from '../client/results.ts';
import { DIALECTS } from '../dialect.ts';
import { encodeInstruction } from '../instructions.ts';
import { BROADCAST_ID, MAX_SERVO_ID, type BusProtocol } from '../protocols.ts';
import { statusProblems, type StatusProblem } from '../status-errors.ts';

/** The line the doctor talks over. */
export interface DoctorLink {
  /** Sets the line's baud rate (reopens a serial port). */
  setBaud(baud: number): Promise<void>;
  /**
   * Writes `bytes`; resolves with every byte that came back within `ms`, or as soon as
   * `expectBytes` have (when given).
   */
  exchange(bytes: Uint8Array, ms: number, expectBytes?: number): Promise<Uint8Array>;
}

/** What one servo said of itself. */
export interface ScannedServo {
  id: number;
  baud: number;
  modelNumber: number;
  firmware: string;
  /** Supply voltage it measures, V. */
  voltageV: number;
  /** The input voltage range it is set for (its EEPROM), V. */
  minVoltageV: number;
  maxVoltageV: number;
  temperatureC: number;
  maxTemperatureC: number;
  /** Its error flags (status byte, and Dynamixel's Hardware Error Status). */
  problems: StatusProblem[];
  /** Homing offset register and present position, ticks. */
  homingOffset: number;
  position: number;
}

export interface BusScan {
  protocol: BusProtocol;
  /** Baud rates tried, and what answered at each. */
  bauds: { baud: number; found: number[]; garbled: number[] }[];
  servos: ScannedServo[];
}

export interface ScanOptions {
  protocol: BusProtocol;
  /** Baud rates to try, first the one in use. */
  bauds: readonly number[];
  /** Ids pinged one by one at a rate where something answers (default: every id). */
  ids?: readonly number[];
  /** Also ping every id at that rate when one of `ids` is missing (default true). */
  searchAll?: boolean;
  /**
   * Stop at the first rate where anything answered (default true); else go on while an id of
   * `ids` has not answered. A servo answers at one rate only, so an id heard at one rate is
   * not asked again at the next.
   */
  stopAtFirst?: boolean;
  /** Wait margin for an answer, ms (USB latency). */
  marginMs?: number;
}

const REGISTERS = {
  feetech: {
    table: STS_TABLE as Record<string, Field>,
    voltUnit: FEETECH_VOLTAGE_UNIT_V,
    blocks: [
      [0, 37],
      [40, 31],
    ],
    firmware: (v: (f: string) => number) =>
      `${v('firmwareMajorVersion')}.${v('firmwareMinorVersion')}`,
    maxTemp: 'maxTemperatureLimit',
    voltage: 'presentVoltage',
    hardwareErrors: undefined,
  },
  dynamixel: {
    table: X_SERIES_TABLE as Record<string, Field>,
    voltUnit: 0.1,
    blocks: [
      [0, 64],
      [70, 1],
      [132, 15],
    ],
    firmware: (v: (f: string) => number) => String(v('firmwareVersion')),
    maxTemp: 'temperatureLimit',
    voltage: 'presentInputVoltage',
    hardwareErrors: 'hardwareErrorStatus',
  },
} as const;

const DYNAMIXEL_HARDWARE_PROBLEMS: [number, StatusProblem][] = [
  [0x01, 'voltage'],
  [0x04, 'overheat'],
  [0x08, 'angle-sensor'],
  [0x10, 'overcurrent'],
  [0x20, 'overload'],
];

export async function scanBus(link: DoctorLink, o: ScanOptions): Promise<BusScan> {
  const { protocol } = o;
  const every = Array.from({ length: MAX_SERVO_ID[protocol] + 1 }, (_, i) => i);
  const client = createBusClient({ protocol, servos: every.map((id) => ({ id })) });
  const scan: BusScan = { protocol, bauds: [], servos: [] };
  const marginMs = o.marginMs ?? 20;
  const heardFrom = new Set<number>();

  for (const baud of o.bauds) {
    await link.setBaud(baud);
    const wait = (bytes: number) => replyTimeoutMs(bytes, baud, marginMs);
    const ask = async (make: (c: BusClient) => Uint8Array): Promise<BusResult | undefined> => {
      const bytes = make(client);
      const expected = client.pending?.expectedReplyBytes ?? 0;
      const reply = await link.exchange(bytes, wait(expected), expected);
      return client.feed(reply)[0] ?? client.expire();
    };
    const broadcast = encodeInstruction(protocol, { op: 'ping', id: BROADCAST_ID });
    const heard = await link.exchange(broadcast, wait(14 * 8));
    const echoed = answeredBroadcast(protocol, heard);
    const row = { baud, found: [] as number[], garbled: [] as number[] };
    scan.bauds.push(row);
    if (heard.length === 0 && o.ids === undefined) continue;
    const ping = async (id: number) => {
      const errorsBefore = Object.values(client.counters.errors).reduce((a, b) => a + b, 0);
      const r = await ask((c) => c.ping(id));
      const errorsAfter = Object.values(client.counters.errors).reduce((a, b) => a + b, 0);
      if (r?.kind === 'ping' && r.found) row.found.push(id);
      else if (errorsAfter > errorsBefore) row.garbled.push(id);
    };
    const first = (o.ids ?? every).filter((id) => !heardFrom.has(id));
    for (const id of first) await ping(id);
    const missing = first.some((id) => !row.found.includes(id));
    // Others: those that answered the broadcast, or every id when its answers were garbled.
    if (o.ids && missing && (o.searchAll ?? true) && heard.length > 0)
      for (const id of echoed.garbled ? every : echoed.ids)
        if (!first.includes(id) && !heardFrom.has(id)) await ping(id);
    for (const id of [...row.found, ...row.garbled]) heardFrom.add(id);
    for (const id of row.found) {
      const servo = await describe(id, baud, ask, protocol);
      if (servo) scan.servos.push(servo);
    }
    if ((o.stopAtFirst ?? true) && (row.found.length || row.garbled.length)) break;
    if (o.ids?.every((id) => heardFrom.has(id))) break;
  }
  return scan;
}

/** The ids in the answers to a broadcast ping, and whether some of it did not read. */
function answeredBroadcast(protocol: BusProtocol, bytes: Uint8Array) {
  const ids: number[] = [];
  let garbled = false;
  const reader = DIALECTS[protocol].createReader({
    direction: 'status',
    onPacket: (p) => (p.type === 'status' ? ids.push(p.id) : undefined),
    onError: () => (garbled = true),
  });
  reader.feed(bytes);
  reader.flush();
  return { ids, garbled };
}

async function describe(
  id: number,
  baud: number,
  ask: (make: (c: BusClient) => Uint8Array) => Promise<BusResult | undefined>,
  protocol: BusProtocol,
): Promise<ScannedServo | undefined> {
  const reg = REGISTERS[protocol];
  const mem = new Uint8Array(256);
  let error = 0;
  for (const [address, length] of reg.blocks) {
    const r = await ask((c) => c.read(id, address, length));
    if (r?.kind !== 'read' || !r.found || !r.data) return undefined;
    mem.set(r.data, address);
    error |= r.status?.error ?? 0;
  }
  const v = (name: string) => decodeField(reg.table[name]!, mem, reg.table[name]!.address);
  const problems = new Set(statusProblems(protocol, error));
  if (reg.hardwareErrors) {
    problems.delete('hardware-alert');
    const bits = v(reg.hardwareErrors);
    for (const [bit, p] of DYNAMIXEL_HARDWARE_PROBLEMS) if (bits & bit) problems.add(p);
  }
  return {
    id,
    baud,
    modelNumber: v('modelNumber'),
    firmware: reg.firmware(v),
    voltageV: v(reg.voltage) * reg.voltUnit,
    minVoltageV: v('minVoltageLimit') * reg.voltUnit,
    maxVoltageV: v('maxVoltageLimit') * reg.voltUnit,
    temperatureC: v('presentTemperature'),
    maxTemperatureC: v(reg.maxTemp),
    problems: [...problems],
    homingOffset: v('homingOffset'),
    position: v('presentPosition'),
  };
}
