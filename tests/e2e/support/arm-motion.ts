/**
 * What the arm does, as a raw MQTT subscriber sees it (tests/e2e/support/sim.ts ArmObserver):
 * one servo's reported pulses report by report, whether it is moving, and whether it has stopped.
 */
import { armTopics } from '@armtwin/protocol';
import type { ArmObserver } from './sim.ts';
import { until } from './sim.ts';

/** Servo `servo`'s pulse in one status payload (NaN if the payload has none). */
function pulseIn(text: string, servo: number): number {
  const m = new RegExp(`#${String(servo).padStart(3, '0')}P(\\d{3,4})!`).exec(text);
  return m ? Number(m[1]) : NaN;
}

/** Status reports of the arm so far (their arrival times and texts). */
export function statusReports(o: ArmObserver): { at: number; text: string }[] {
  const topic = armTopics(o.armId).status;
  return o.messages.filter((m) => m.topic === topic);
}

/** Waits for `n` more status reports and gives servo `servo`'s pulses in them. */
export async function nextPulses(o: ArmObserver, servo: number, n: number): Promise<number[]> {
  const from = statusReports(o).length;
  await until(() => statusReports(o).length >= from + n, 20_000, `${n} status reports`);
  return statusReports(o)
    .slice(from, from + n)
    .map((m) => pulseIn(m.text, servo))
    .filter(Number.isFinite);
}

/** Waits until servo `servo` is more than `by` µs from `from` (it moves). */
export async function movedFrom(o: ArmObserver, servo: number, from: number, by = 15) {
  await until(() => Math.abs(o.pwm[servo]! - from) > by, 15_000, `servo ${servo} to move`);
  return o.pwm[servo]!;
}

/**
 * Whether the servo has stopped: of the next 20 reports, the last 15 all say the same pulse (the
 * first 5 leave time for what was already on its way).
 */
export async function holdsStill(o: ArmObserver, servo: number): Promise<boolean> {
  const p = await nextPulses(o, servo, 20);
  return p.length >= 15 && new Set(p.slice(-15)).size === 1;
}

/** Control payloads since `since` that move servo `servo` (`#IIIP…T…!`, alone or in a group). */
export function movesOf(o: ArmObserver, servo: number, since: number): string[] {
  const re = new RegExp(`#${String(servo).padStart(3, '0')}[PA][+-]?\\d`);
  return o.commands(since).filter((t) => re.test(t) && !t.includes('PDST'));
}
