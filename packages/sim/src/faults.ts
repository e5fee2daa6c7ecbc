/**
 * Fault injection for tests and demos. The same commands come from CLI flags at start-up and,
 * at runtime, as JSON on `arm/{id}/sim` (one object or an array of them):
 *
 *   {"fault":"stall","id":1}                 servo 001 jams where it is (and heats as it pushes)
 *   {"fault":"overheat","id":2,"celsius":85} servo 002 heats towards 85 °C (default 85)
 *   {"fault":"undervolt","mv":6200}          the supply can give at most 6200 mV (0 = off)
 *   {"fault":"drop","percent":20}            drop 20 % of state samples (0 = off)
 *   {"fault":"latency","ms":50}              delay every payload out and every command in by 50 ms
 *   {"fault":"clear","id":2}                 un-stall and cool servo 002
 *   {"fault":"clear"}                        clear every fault
 */
import { z } from 'zod';
import type { SimModel } from './model.ts';

const servoId = z.number().int().min(0).max(254);

export const FAULT_SCHEMA = z.discriminatedUnion('fault', [
  z.object({ fault: z.literal('stall'), id: servoId }),
  z.object({
    fault: z.literal('overheat'),
    id: servoId,
    celsius: z.number().min(0).max(999).optional(),
  }),
  z.object({ fault: z.literal('undervolt'), mv: z.number().int().min(0).max(9999) }),
  z.object({ fault: z.literal('drop'), percent: z.number().min(0).max(100) }),
  z.object({ fault: z.literal('latency'), ms: z.number().int().min(0).max(60_000) }),
  z.object({ fault: z.literal('clear'), id: servoId.optional() }),
]);

export type Fault = z.infer<typeof FAULT_SCHEMA>;

/** The faults in force, as published (retained) on `arm/{id}/sim/faults`. */
export interface FaultState {
  stalled: number[];
  /** servo id → target °C */
  overheated: Record<string, number>;
  undervoltMv: number;
  dropPercent: number;
  latencyMs: number;
}

export const NO_FAULTS: FaultState = {
  stalled: [],
  overheated: {},
  undervoltMv: 0,
  dropPercent: 0,
  latencyMs: 0,
};

/** Parses a runtime fault message: one fault or an array. Throws with a readable message. */
export function parseFaults(text: string): Fault[] {
  let json: unknown;
  try {
    json = JSON.parse(text);
  } catch {
    throw new Error(`not JSON: ${text.slice(0, 80)}`);
  }
  const list = Array.isArray(json) ? json : [json];
  return list.map((item) => {
    const r = FAULT_SCHEMA.safeParse(item);
    if (!r.success) {
      throw new Error(
        `bad fault ${JSON.stringify(item).slice(0, 80)}: ${r.error.issues[0]?.message ?? 'invalid'}`,
      );
    }
    return r.data;
  });
}

/**
 * Applies a fault at time t: servo faults to the model, link faults to `state` (which the
 * runner reads). Returns the new state; throws for a servo the arm does not have.
 */
export function applyFault(
  model: SimModel,
  state: FaultState,
  f: Fault,
  t: number,
  defaultOverheatC: number,
): FaultState {
  const s = model.servos;
  const index = (id: number) => {
    const i = s.indexOf(id);
    if (i < 0) throw new Error(`no servo ${id}`);
    return i;
  };
  model.advance(t);
  const next: FaultState = {
    ...state,
    stalled: [...state.stalled],
    overheated: { ...state.overheated },
  };
  switch (f.fault) {
    case 'stall':
      s.setStalled(index(f.id), true, t);
      if (!next.stalled.includes(f.id)) next.stalled.push(f.id);
      break;
    case 'overheat': {
      const c = f.celsius ?? defaultOverheatC;
      s.overheat[index(f.id)] = c;
      next.overheated[String(f.id)] = c;
      break;
    }
    case 'undervolt':
      s.supplyLimitMv = f.mv > 0 ? f.mv : NaN;
      next.undervoltMv = f.mv;
      break;
    case 'drop':
      next.dropPercent = f.percent;
      break;
    case 'latency':
      next.latencyMs = f.ms;
      break;
    case 'clear':
      for (let i = 0; i < s.count; i++) {
        if (f.id !== undefined && s.ids[i] !== f.id) continue;
        s.setStalled(i, false, t);
        s.overheat[i] = NaN;
      }
      if (f.id === undefined)
        return applyFault(
          model,
          { ...NO_FAULTS },
          { fault: 'undervolt', mv: 0 },
          t,
          defaultOverheatC,
        );
      next.stalled = next.stalled.filter((id) => id !== f.id);
      delete next.overheated[String(f.id)];
      break;
  }
  return next;
}
