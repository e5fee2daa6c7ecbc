import { describe, expect, it } from 'vitest';
import fc from 'fast-check';
import { ClockOffset } from '../src/core/store/ClockOffset.ts';
import { JointPredictor } from '../src/core/store/JointPredictor.ts';
import { TwinPredictor } from '../src/core/store/TwinPredictor.ts';
import { ArmStore } from '../src/core/store/ArmStore.ts';
import { applyQuery, defaultSettings } from '../src/core/config/settings.ts';
import { DEMO_ARM } from '@armtwin/ik';
import { angleFromPwm } from '@armtwin/protocol';
import { drawnLeadMs } from '../src/scene/render/SceneReports.ts';

/** The controller's motion (packages/sim/src/servos.ts): linear to the target, speed-limited. */
function simMove(from: number, to: number, durMs: number, vmaxDegPerMs: number) {
  const dur = Math.max(durMs, Math.abs(to - from) / vmaxDegPerMs);
  return (t: number) => (t <= 0 ? from : t >= dur ? to : from + ((to - from) * t) / dur);
}

const EPOCH = 1_700_000_000_000;
const VMAX = 375 / 1000; // § 4: 60° per 0.16 s, ° per ms

describe('ClockOffset', () => {
  it('takes the smallest arrival − stamp, so late arrivals do not bias it', () => {
    const c = new ClockOffset();
    expect(c.offsetMs).toBeNaN();
    const delays = [7, 1.5, 30, 2, 120, 1.5, 4];
    delays.forEach((d, k) => c.add(100 + k * 20 + d, EPOCH + k * 20));
    expect(c.offsetMs).toBeCloseTo(100 - EPOCH + 1.5, 6);
    expect(c.armTime(500)).toBeCloseTo(EPOCH + 400 - 1.5, 6);
  });

  it('forgets a minimum older than its window, and starts over when the arm clock goes back', () => {
    const c = new ClockOffset({ bucketMs: 100, buckets: 3 });
    c.add(0, EPOCH); // offset −EPOCH
    c.add(1000, EPOCH + 990); // 10 ms later than before: the first bucket has left the window
    expect(c.offsetMs).toBeCloseTo(10 - EPOCH, 6);
    c.add(1010, EPOCH - 5000);
    expect(c.offsetMs).toBeCloseTo(1010 - EPOCH + 5000, 6);
  });
});

describe('JointPredictor', () => {
  it('moves a report on along the command, up to the target and no further', () => {
    const j = new JointPredictor(-135, 135, VMAX);
    j.report(0, 0);
    j.command(40, 1000, 0);
    expect(j.predict(10)).toBeCloseTo(0.4, 6);
    j.report(20, 0.8);
    expect(j.predict(30)).toBeCloseTo(1.2, 6);
    j.report(990, 39.6);
    expect(j.predict(1050)).toBe(40);
  });

  it('does not run past the target from a report exactly on it', () => {
    // Off the command's course (it started late), the reports' velocity carries the joint on;
    // the newest report is on the target pulse itself: it stays there. Both ways.
    for (const [from, to] of [
      [0, 40],
      [40, 0],
    ] as const) {
      const j = new JointPredictor(-135, 135, VMAX);
      const step = (to - from) / 20;
      j.report(0, from);
      j.command(to, 1000, 0);
      j.report(600, to - 2 * step);
      j.report(620, to - step);
      j.report(640, to);
      expect(j.following).toBe(false);
      expect(j.predict(700)).toBe(to);
    }
  });

  it('respects the top speed when the commanded time is shorter', () => {
    const j = new JointPredictor(-135, 135, VMAX);
    j.report(0, 0);
    j.command(120, 0, 0); // 120° at 375°/s: 320 ms
    expect(j.predict(100)).toBeCloseTo(37.5, 6);
  });

  it('keeps to the course when the arm begins the command after the next report', () => {
    // Reports at 5 Hz; the page saw the command at 4.8 ms, the arm began it at 35 ms (the
    // command's way to the arm on a loaded machine), after the report at 17 ms still showed
    // it where it was (seen on a fresh clone: the twin then left the course and jumped).
    const j = new JointPredictor(-135, 135, VMAX);
    const v = 80 / 4000;
    const truth = (t: number) => Math.max(0, (t - 35) * v);
    j.report(-183, 0);
    j.command(80, 4000, 4.8);
    for (let t = 17; t <= 1417; t += 200) {
      j.report(t, truth(t));
      expect(j.following).toBe(true);
      // From the first report that shows the move, the course is the arm's own.
      if (t > 17)
        for (let dt = 0; dt < 200; dt += 50) expect(j.predict(t + dt)).toBeCloseTo(truth(t + dt), 6);
    }
  });

  it('follows a command that never begins once the arm had time to take it', () => {
    const j = new JointPredictor(-135, 135, VMAX);
    j.report(0, 0);
    j.command(40, 1000, 0);
    for (let t = 20; t <= 400; t += 20) j.report(t, 0);
    expect(j.following).toBe(false);
    expect(j.predict(410)).toBe(0);
  });

  it('follows a stall at the first report that shows it', () => {
    const j = new JointPredictor(-135, 135, VMAX);
    const truth = simMove(0, 60, 1000, VMAX);
    for (let t = 0; t <= 200; t += 20) {
      if (t === 20) j.command(60, 1000, 0);
      j.report(t, truth(t));
    }
    expect(j.predict(210)).toBeCloseTo(truth(210), 6);
    // Jammed at t = 205: the report at 220 says so, and the prediction holds it there.
    j.report(220, truth(205));
    expect(j.following).toBe(false);
    expect(j.predict(225)).toBeCloseTo(truth(205), 6);
    j.report(240, truth(205));
    expect(j.predict(259)).toBe(truth(205));
  });

  it('extrapolates the reported velocity when no command was seen, and holds after a stop', () => {
    const j = new JointPredictor(-135, 135, VMAX);
    j.report(0, 10);
    j.report(20, 11);
    expect(j.predict(30)).toBeCloseTo(11.5, 6);
    j.stop(25);
    expect(j.predict(30)).toBeCloseTo(11.25, 6);
  });

  it('never passes the commanded target nor the limits, whatever the reports (property)', () => {
    fc.assert(
      fc.property(
        fc.double({ min: -135, max: 135, noNaN: true }),
        fc.double({ min: -200, max: 200, noNaN: true }),
        fc.integer({ min: 0, max: 3000 }),
        // Reports within the limits (a report is drawn as it came; the prediction is bounded).
        fc.array(fc.double({ min: -90, max: 90, noNaN: true }), { minLength: 1, maxLength: 8 }),
        fc.integer({ min: 0, max: 500 }),
        (start, target, dur, reports, ahead) => {
          const j = new JointPredictor(-90, 90, VMAX);
          j.report(0, Math.min(90, Math.max(-90, start)));
          j.command(target, dur, 5);
          const t0 = Math.min(90, Math.max(-90, target));
          let t = 0;
          for (const r of reports) {
            t += 20;
            j.report(t, r);
            const p = j.predict(t + ahead);
            if (!(p >= -90 && p <= 90)) return false;
            // Ahead of the newest report, never beyond the target on the way to it.
            if ((t0 - r) * (p - t0) > 1e-9) return false;
          }
          return true;
        },
      ),
    );
  });

  it('a stall during any move is drawn as reported within one report interval (property)', () => {
    fc.assert(
      fc.property(
        fc.double({ min: -100, max: 100, noNaN: true }),
        fc.double({ min: -100, max: 100, noNaN: true }),
        fc.integer({ min: 200, max: 3000 }),
        fc.integer({ min: 1, max: 50 }),
        fc.double({ min: 0.1, max: 0.9, noNaN: true }),
        (from, to, dur, interval, stallAt) => {
          const free = simMove(from, to, dur, VMAX);
          const total = Math.max(dur, Math.abs(to - from) / VMAX);
          const jam = stallAt * total;
          const truth = (t: number) => free(Math.min(t, jam));
          const j = new JointPredictor(-135, 135, VMAX);
          j.report(-interval, from);
          j.command(to, dur, 0);
          // Reports until one is visibly off the free course (by more than 1 µs + 0.05°).
          let t = 0;
          for (; t < total; t += interval) {
            j.report(t, truth(t));
            if (Math.abs(free(t) - truth(t)) > 0.2) break;
          }
          if (!(t < total)) return true; // the move ended before the stall showed
          // One report interval later (the stall may have begun inside the interval the
          // command's course was measured over), every frame draws the joint as reported.
          t += interval;
          j.report(t, truth(t));
          for (let dt = 0; dt < interval; dt += interval / 4)
            if (Math.abs(j.predict(t + dt) - truth(t)) > 1e-9) return false;
          return true;
        },
      ),
    );
  });
});

describe('TwinPredictor', () => {
  it('predicts on the arm clock and says when the pose is ahead of the reports', () => {
    const p = new TwinPredictor([{ minDeg: -135, maxDeg: 135, maxSpeedDegPerS: 375 }]);
    const out = new Float64Array(1);
    // Reports stamped on the arm clock arrive 3 ms (or more) later on the page clock.
    const stamp0 = p.arrive(EPOCH, 103);
    p.report(0, stamp0, 0);
    p.command(0, 30, 1000, 103);
    p.sample(103, out);
    expect(out[0]).toBeCloseTo(0, 6);
    expect(p.predicting).toBe(false);
    p.report(0, p.arrive(EPOCH + 20, 140), 0.6);
    p.sample(133, out); // the arm's time is EPOCH + 30
    expect(out[0]).toBeCloseTo(0.9, 6);
    expect(p.predicting).toBe(true);
    expect(p.leadMs).toBeCloseTo(10, 6);
  });
});

describe('ArmStore in predict mode', () => {
  const state = (pwm: number[]) => `{${pwm.map((p, i) => `#00${i}P${p}!`).join('')}}`;

  it('draws the commanded move ahead of the reports and stops with the stop', () => {
    const s = new ArmStore();
    expect(s.opts.twinMode).toBe('predict');
    const rest = [1500, 1500, 1500, 1500, 1500, 1500];
    s.ingest(`$TIM:${EPOCH}!${state(rest)}`, 1000);
    s.noteControl('{#000P2000T1000!}', 1000);
    s.ingest(`$TIM:${EPOCH + 20}!${state([1510, ...rest.slice(1)])}`, 1021);
    s.sample(1030);
    const v = angleFromPwm(2000, DEMO_ARM.servos[0]!.polarity) / 1000; // ° per ms
    expect(s.rendered[0]).toBeCloseTo(angleFromPwm(1510, 1) + v * 10, 1);
    expect(s.predicting).toBe(true);
    expect(s.predictionLeadMs).toBeGreaterThan(0);
    // A renderer that draws later along the course (the worker) adds its own lead.
    const sampled = s.predictionLeadMs;
    expect(drawnLeadMs(s, { aheadMs: 12 })).toBeCloseTo(sampled + 12, 9);
    s.noteControl('#255PDST!', 1031);
    s.ingest(`$TIM:${EPOCH + 40}!${state([1520, ...rest.slice(1)])}`, 1041);
    s.ingest(`$TIM:${EPOCH + 60}!${state([1520, ...rest.slice(1)])}`, 1061);
    s.sample(1075);
    expect(s.rendered[0]).toBe(angleFromPwm(1520, 1));
    expect(s.predicting).toBe(false);
  });
});

describe('twin mode setting', () => {
  const loc = { protocol: 'http:', host: 'hud.example:8080' };

  it('defaults to predict; ?twin= picks another mode and ignores an unknown one', () => {
    expect(defaultSettings(loc).twinMode).toBe('predict');
    expect(applyQuery(defaultSettings(loc), '?twin=interpolate').twinMode).toBe('interpolate');
    expect(applyQuery(defaultSettings(loc), '?twin=newest').twinMode).toBe('newest');
    expect(applyQuery(defaultSettings(loc), '?twin=guess').twinMode).toBe('predict');
  });

  it('draws each report as it came in newest mode', () => {
    const s = new ArmStore({ twinMode: 'newest' });
    s.ingest(`$TIM:${EPOCH}!{#000P1500!#001P1500!#002P1500!#003P1500!#004P1500!#005P1500!}`, 0);
    s.noteControl('#000P2000T1000!', 0);
    s.ingest(
      `$TIM:${EPOCH + 20}!{#000P1510!#001P1500!#002P1500!#003P1500!#004P1500!#005P1500!}`,
      20,
    );
    s.sample(35);
    expect(s.rendered[0]).toBe(angleFromPwm(1510, 1));
    expect(s.predicting).toBe(false);
  });
});
