/**
 * Faults of the bench rather than the servo, for the emulated bus (`armtwin sim --bus …
 * --bus-fault KIND:ID[:FIELD=VALUE]`), so the servo doctor's every finding can be shown on a
 * simulated arm: a servo `absent` from the chain, an `extra` one, a second servo `clash`ing on
 * an id, and any control-table `field` of a servo (a 7.4 V servo's voltage limit
 * `maxVoltageLimit=80`, the supply it measures `presentVoltage=121`, a firmware, a model
 * number, Feetech's Status error bits `status=32` for an overload).
 */
import type { EmulatedServoSpec } from './emulated-bus.ts';

export type BenchFault =
  | { kind: 'absent' | 'extra' | 'clash'; id: number }
  | { kind: 'field'; id: number; field: string; value: number };

/** Reads `KIND:ID` or `field:ID:FIELD=VALUE`; throws with the accepted forms otherwise. */
export function parseBenchFault(text: string): BenchFault {
  const m = /^(absent|extra|clash|field):(\d{1,3})(?::([A-Za-z]+)=(-?\d+))?$/.exec(text.trim());
  const id = Number(m?.[2]);
  if (!m || id > 253 || (m[1] === 'field') !== (m[3] !== undefined))
    throw new Error(
      `bus fault "${text}": absent:ID, extra:ID, clash:ID or field:ID:FIELD=VALUE (e.g. field:2:maxVoltageLimit=80)`,
    );
  return m[1] === 'field'
    ? { kind: 'field', id, field: m[3]!, value: Number(m[4]) }
    : { kind: m[1] as 'absent' | 'extra' | 'clash', id };
}

/** The servos on the bus once the bench faults are applied to `servos` (the profile's). */
export function withBenchFaults(
  servos: readonly EmulatedServoSpec[],
  faults: readonly BenchFault[],
): { servos: EmulatedServoSpec[]; idClash: 'refuse' | 'collide' } {
  let out: EmulatedServoSpec[] = servos.map((s) => ({ ...s, fields: { ...s.fields } }));
  let idClash: 'refuse' | 'collide' = 'refuse';
  for (const f of faults) {
    const like: EmulatedServoSpec = out.find((s) => s.id === f.id) ?? out[0] ?? { id: f.id };
    if (f.kind === 'field') {
      for (const s of out) if (s.id === f.id) s.fields = { ...s.fields, [f.field]: f.value };
    } else if (f.kind === 'absent') out = out.filter((s) => s.id !== f.id);
    else {
      out.push({ ...like, id: f.id });
      if (f.kind === 'clash') idClash = 'collide';
    }
  }
  return { servos: out, idClash };
}
