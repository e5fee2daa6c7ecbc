import { describe, expect, it } from 'vitest';
import { angleFromPwm } from '@armtwin/protocol';
import { DEMO_ARM } from '@armtwin/ik';
import { StreamRecorder } from '../lib/stream-recorder.ts';
import { frameErrors } from '../lib/fidelity.ts';
import type { ProbeResult } from '../lib/page-probe.ts';

/** A stamped state group of `pwm` (one pulse per servo) as the simulator publishes it. */
const group = (t: number, pwm: number[]) =>
  Buffer.from(`$TIM:${t}!{${pwm.map((p, i) => `#00${i}P${p}!`).join('')}}`, 'latin1');

/** A probe record of frames at wall times `wall`, each showing `stamp` and drawing `angles`. */
function probe(wall: number[], stamp: number[], angles: number[][]): ProbeResult {
  return {
    frames: wall.length,
    wall,
    stamp,
    angles: angles.flat(),
    servoCount: angles[0]!.length,
  } as ProbeResult;
}

describe('bench fidelity', () => {
  it('reads the true angle between samples, and nothing outside the record', () => {
    const rec = new StreamRecorder(2);
    rec.feed(group(1000, [1500, 1500])); // off: not recorded
    rec.on = true;
    rec.feed(group(1000, [1500, 1500]));
    rec.feed(group(1000, [1500])); // a group of another size: skipped
    rec.feed(group(1100, [1600, 1400]));
    expect(rec.stamp).toEqual([1000, 1100]);
    expect(rec.arrivalMinusStamp).toHaveLength(2);
    const halfway = angleFromPwm(1550, DEMO_ARM.servos[0]!.polarity);
    expect(rec.angleAt(0, 1050)).toBeCloseTo(halfway, 9);
    expect(Number.isNaN(rec.angleAt(0, 999))).toBe(true);
    rec.clear();
    expect([rec.stamp.length, rec.pwm.length, rec.arrivalMinusStamp.length]).toEqual([0, 0, 0]);
  });

  it('counts a drawn angle against the truth at its frame, beside the newest sample held', () => {
    const rec = new StreamRecorder(1);
    rec.on = true;
    rec.feed(group(1000, [1500]));
    rec.feed(group(1100, [1600]));
    const truthAt = (t: number) => rec.angleAt(0, t);
    // Two frames showing the same report, then one showing a newer one.
    const p = probe(
      [1050, 1060, 1100],
      [1000, 1000, 1100],
      [[truthAt(1050) + 1], [truthAt(1060)], [truthAt(1100)]],
    );
    const e = frameErrors(p, rec, 1);
    expect(e.drawn.map((x) => Math.round(x * 1e6) / 1e6)).toEqual([1, 0, 0]);
    expect(e.newest[0]).toBeCloseTo(Math.abs(truthAt(1050) - truthAt(1000)), 9);
    expect(e.latency).toEqual([50, 0]); // only frames showing a newer report
  });
});
