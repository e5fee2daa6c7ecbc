/**
 * The servo doctor's findings (pure): what a bus scan (scan.ts) says is wrong, each in plain
 * words with its fix, for the failures bus-servo arms meet most (LeRobot's reports among
 * them: "Incorrect status packet" lerobot#1010, "Input voltage error" while setting ids #2387,
 * a calibration overflow #1296). One finding per kind and cause, naming the servos.
 */
import { DYNAMIXEL_MODELS } from '../dynamixel/control-table.ts';
import { FEETECH_MODELS } from '../feetech/control-table.ts';
import type { BusScan, ScannedServo } from './scan.ts';

export const FINDING_KINDS = [
  'no-servos',
  'baud',
  'garbled',
  'missing',
  'extra',
  'model',
  'firmware',
  'voltage-variant',
  'undervoltage',
  'mixed-variants',
  'overheat',
  'overload',
  'calibration-overflow',
] as const;
export type FindingKind = (typeof FINDING_KINDS)[number];

export interface Finding {
  kind: FindingKind;
  /** `error`: the arm will not work right; `warning`: it may, but fix it. */
  severity: 'error' | 'warning';
  ids: number[];
  finding: string;
  fix: string;
}

export interface DoctorExpectation {
  /** The baud rate the gateway uses. */
  baud: number;
  /** The profile's servo ids. */
  ids: readonly number[];
}

/** Ticks from the encoder's wrap under which a calibration overflows or a range crosses it. */
export const WRAP_MARGIN_TICKS = 100;

const list = (ids: readonly number[]) => ids.join(', ');
const byKind = (servos: ScannedServo[], key: (s: ScannedServo) => string) => {
  const groups = new Map<string, number[]>();
  for (const s of servos) groups.set(key(s), [...(groups.get(key(s)) ?? []), s.id]);
  return groups;
};

export function diagnoseBus(scan: BusScan, expect: DoctorExpectation): Finding[] {
  const out: Finding[] = [];
  const add = (f: Finding) => out.push(f);
  const found = scan.bauds.flatMap((b) => b.found);
  const garbled = scan.bauds.flatMap((b) => b.garbled);
  const vendor = scan.protocol === 'feetech' ? 'Feetech' : 'Dynamixel';
  if (found.length === 0 && garbled.length === 0)
    add({
      kind: 'no-servos',
      severity: 'error',
      ids: [],
      finding: `no servo answered at ${scan.bauds.map((b) => b.baud).join(', ')} baud`,
      fix: `check the servos' supply is on (the adapter's power input, not USB), the bus cable is in the adapter's ${vendor} port, and --serial names the adapter; try another --bus if these are not ${vendor} servos`,
    });
  for (const b of scan.bauds)
    if (b.baud !== expect.baud && b.found.length)
      add({
        kind: 'baud',
        severity: 'error',
        ids: b.found,
        finding: `servos ${list(b.found)} answer at ${b.baud} baud, the gateway uses ${expect.baud}`,
        fix: `start the gateway with --baud ${b.baud}, or set every servo to ${expect.baud} baud with the vendor's tool`,
      });
  if (garbled.length)
    add({
      kind: 'garbled',
      severity: 'error',
      ids: garbled,
      finding: `id ${list(garbled)} answered with a garbled packet (LeRobot: "Incorrect status packet", lerobot#1010): two servos share that id, or the line is noisy or underpowered`,
      fix: `connect one servo at a time and give each its own id (lerobot-setup-motors, or the vendor's tool: new servos all come as id 1); then check the supply's current and the cables`,
    });
  const missing = expect.ids.filter((id) => !found.includes(id) && !garbled.includes(id));
  if (missing.length && found.length)
    add({
      kind: 'missing',
      severity: 'error',
      ids: missing,
      finding: `servos ${list(missing)} of the profile did not answer`,
      fix: `check each one's cable and id (a servo not yet given its id answers as 1); the others answered, so the bus and supply work`,
    });
  const extra = found.filter((id) => !expect.ids.includes(id));
  if (extra.length)
    add({
      kind: 'extra',
      severity: 'warning',
      ids: extra,
      finding: `servos ${list(extra)} answered but are not in the profile`,
      fix: missing.length
        ? `give them the profile's missing ids (${list(missing)}) with lerobot-setup-motors or the vendor's tool`
        : `take them off this bus or add them to the profile`,
    });
  const servos = scan.servos;
  const models = scan.protocol === 'feetech' ? FEETECH_MODELS : DYNAMIXEL_MODELS;
  const unknown = servos.filter((s) => !models.some((m) => m.modelNumber === s.modelNumber));
  if (unknown.length)
    add({
      kind: 'model',
      severity: 'error',
      ids: unknown.map((s) => s.id),
      finding: `servos ${list(unknown.map((s) => s.id))} report model ${list([...new Set(unknown.map((s) => s.modelNumber))])}, not a model armtwin knows (${models.map((m) => `${m.name} ${m.modelNumber}`).join(', ')})`,
      fix: `use the servo model the arm is built for; another model's control table differs`,
    });
  const firmwares = byKind(servos, (s) => s.firmware);
  if (firmwares.size > 1)
    add({
      kind: 'firmware',
      severity: 'warning',
      ids: servos.map((s) => s.id),
      finding: `the servos run different firmware: ${[...firmwares].map(([f, ids]) => `${f} on ${list(ids)}`).join('; ')} (LeRobot refuses such a bus)`,
      fix: `update them all to the same firmware with the vendor's tool (Feetech FD, Dynamixel Wizard)`,
    });
  const over = servos.filter((s) => s.voltageV > s.maxVoltageV);
  if (over.length)
    add({
      kind: 'voltage-variant',
      severity: 'error',
      ids: over.map((s) => s.id),
      finding: `servos ${list(over.map((s) => s.id))} measure ${Math.max(...over.map((s) => s.voltageV)).toFixed(1)} V but are made for at most ${Math.min(...over.map((s) => s.maxVoltageV)).toFixed(1)} V ("Input voltage error", lerobot#2387): a higher-voltage supply on lower-voltage servos (a 12 V supply on 7.4 V STS3215s)`,
      fix: `switch the supply off now; use the supply the servos are made for (5–7.4 V for the 7.4 V STS3215, 12 V for the 12 V ones), or servos made for this supply`,
    });
  const under = servos.filter((s) => s.voltageV < s.minVoltageV);
  if (under.length)
    add({
      kind: 'undervoltage',
      severity: 'error',
      ids: under.map((s) => s.id),
      finding: `servos ${list(under.map((s) => s.id))} measure ${Math.min(...under.map((s) => s.voltageV)).toFixed(1)} V, under the ${Math.max(...under.map((s) => s.minVoltageV)).toFixed(1)} V they need`,
      fix: `use a supply of the servos' voltage that gives enough current (several amperes for six servos), and a short, thick power cable`,
    });
  const variants = byKind(servos, (s) => s.maxVoltageV.toFixed(1));
  if (variants.size > 1)
    add({
      kind: 'mixed-variants',
      severity: 'warning',
      ids: servos.map((s) => s.id),
      finding: `servos made for different voltages share this bus: ${[...variants].map(([v, ids]) => `up to ${v} V: ${list(ids)}`).join('; ')}`,
      fix: `one supply cannot suit both: use servos of one voltage on a bus (a leader arm's 7.4 V servos on their own bus)`,
    });
  const hot = servos.filter(
    (s) => s.problems.includes('overheat') || s.temperatureC >= s.maxTemperatureC,
  );
  if (hot.length)
    add({
      kind: 'overheat',
      severity: 'error',
      ids: hot.map((s) => s.id),
      finding: `servos ${list(hot.map((s) => s.id))} are overheating (${hot.map((s) => `${s.id}: ${s.temperatureC} °C, limit ${s.maxTemperatureC} °C`).join('; ')}): they drop torque`,
      fix: `turn torque off and let them cool; then find what makes them work hard (a joint pushing against a stop or the table, a load too heavy, a pose held against gravity)`,
    });
  const loaded = servos.filter(
    (s) => s.problems.includes('overload') || s.problems.includes('overcurrent'),
  );
  if (loaded.length)
    add({
      kind: 'overload',
      severity: 'error',
      ids: loaded.map((s) => s.id),
      finding: `servos ${list(loaded.map((s) => s.id))} report an overload: they could not hold or reach their goal`,
      fix: `free the joint (a jam, a collision, a cable caught), then power the servos off and on to clear the flag`,
    });
  const wrap = servos.filter((s) => {
    const shaft = s.position + s.homingOffset;
    return Math.abs(shaft - 2048) > 2048 - WRAP_MARGIN_TICKS;
  });
  if (wrap.length)
    add({
      kind: 'calibration-overflow',
      severity: 'warning',
      ids: wrap.map((s) => s.id),
      finding: `servos ${list(wrap.map((s) => s.id))} sit next to their encoder's wrap (${wrap.map((s) => `${s.id}: tick ${s.position + s.homingOffset} of 4096`).join('; ')}): a calibration there overflows the homing offset (LeRobot: "Magnitude … exceeds 2047", lerobot#1296) and the joint's range crosses the wrap`,
      fix: `move the joint to the middle of its travel before calibrating; if it is there already, take the horn off and put it back so the middle reads near 2048`,
    });
  return out;
}

/** Findings counted by kind. */
export function countFindings(findings: readonly Finding[]): Partial<Record<FindingKind, number>> {
  const out: Partial<Record<FindingKind, number>> = {};
  for (const f of findings) out[f.kind] = (out[f.kind] ?? 0) + 1;
  return out;
}
