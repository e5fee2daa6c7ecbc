import { describe, expect, it } from 'vitest';
import { servoHealth } from '../src/core/store/healthWords.ts';
import { renderWords } from '../src/ui/panels/Status/words.ts';
import { applyQuery, defaultSettings, validateSettings } from '../src/core/config/settings.ts';
import { parseTarget } from '../src/core/cartesian/parseTarget.ts';
import { ghostPose } from '../src/core/store/ghostPose.ts';
import { DEMO_ARM } from '@armtwin/ik';

describe('servoHealth: thresholds of §5 → level and words', () => {
  it.each([
    [45, 7400, 'normal', 'normal', 'normal'],
    [59.9, 7400, 'normal', 'normal', 'normal'],
    [60, 7400, 'warning', 'normal', 'warning'],
    [75, 7400, 'warning', 'normal', 'warning'],
    [76, 7400, 'critical', 'normal', 'critical'],
    [40, 6500, 'normal', 'normal', 'normal'],
    [40, 6499, 'normal', 'critical', 'critical'],
    [65, 6000, 'warning', 'critical', 'critical'],
  ])('%s °C, %s mV → temp %s, voltage %s, overall %s', (t, mv, tl, vl, l) => {
    const h = servoHealth('Elbow', t, mv);
    expect([h.temperatureLevel, h.voltageLevel, h.level]).toEqual([tl, vl, l]);
    expect(h.words.startsWith('Elbow: ')).toBe(true);
  });

  it('says what to do when critical, in words', () => {
    expect(servoHealth('Shoulder', 80, 7400).words).toBe(
      'Shoulder: temperature 80 °C, critical, overheating — cut the power; voltage 7.40 V, normal.',
    );
    expect(servoHealth('Base', 30, 6200).words).toContain('voltage 6.20 V, critical, below 6.5 V');
    expect(servoHealth('Base', NaN, NaN).level).toBe('unknown');
  });
});

describe('settings', () => {
  const base = defaultSettings({ protocol: 'https:', host: 'arm.example:8443' });
  it('defaults to the same origin /mqtt and arm1', () => {
    expect(base.brokerUrl).toBe('wss://arm.example:8443/mqtt');
    expect(base.armId).toBe('arm1');
    expect(defaultSettings({ protocol: 'http:', host: 'h' }).brokerUrl).toBe('ws://h/mqtt');
  });
  it('takes broker and arm from the query, ignoring bad values', () => {
    const s = applyQuery(base, '?broker=ws://127.0.0.1:9001&arm=arm-7&alpha=2');
    expect([s.brokerUrl, s.armId, s.interpolationAlpha]).toEqual([
      'ws://127.0.0.1:9001',
      'arm-7',
      2,
    ]);
    const bad = applyQuery(base, '?broker=http://x&arm=ARM!&alpha=-1');
    expect([bad.brokerUrl, bad.armId, bad.interpolationAlpha]).toEqual([base.brokerUrl, 'arm1', 1]);
  });
  it('validates what the user typed', () => {
    expect(validateSettings(base)).toBeNull();
    expect(validateSettings({ ...base, brokerUrl: 'mqtt://x' })).toMatch(/ws:\/\//);
    expect(validateSettings({ ...base, armId: 'Arm 1' })).toMatch(/Arm id/);
  });
});

describe('parseTarget', () => {
  it('reads numbers, pitch optional', () => {
    expect(parseTarget({ x: '200', y: '-12.5', z: '40', pitch: '' })).toEqual({
      ok: true,
      x: 200,
      y: -12.5,
      z: 40,
      pitch: undefined,
    });
    expect(parseTarget({ x: '1', y: '2', z: '3', pitch: '-90' })).toMatchObject({
      ok: true,
      pitch: -90,
    });
  });
  it('rejects blanks, non-numbers and out-of-range pitch with a message', () => {
    expect(parseTarget({ x: '', y: '0', z: '0', pitch: '' })).toMatchObject({
      ok: false,
      error: 'X must be a number (mm).',
    });
    expect(parseTarget({ x: '1', y: 'abc', z: '0', pitch: '' })).toMatchObject({ ok: false });
    expect(parseTarget({ x: '1', y: '0', z: '0', pitch: '120' })).toMatchObject({ ok: false });
  });
});

describe('ghostPose', () => {
  const rendered = [0, 0, 0, 0, 0, 0];
  const none = new Float64Array(6).fill(NaN);
  it('hides when nothing is commanded or the arm is there', () => {
    const out = new Float64Array(6);
    expect(
      ghostPose(
        { arm: DEMO_ARM, rendered, commandedPwm: none, previewOk: false, previewAngles: [] },
        out,
      ),
    ).toBe('nothing');
    const cmd = new Float64Array(6).fill(1500);
    expect(
      ghostPose(
        { arm: DEMO_ARM, rendered, commandedPwm: cmd, previewOk: false, previewAngles: [] },
        out,
      ),
    ).toBe('nothing');
  });
  it('shows the commanded pose while the arm is away from it', () => {
    const out = new Float64Array(6);
    const cmd = new Float64Array(6).fill(NaN);
    cmd[2] = 1500 + (2000 / 270) * 45;
    expect(
      ghostPose(
        { arm: DEMO_ARM, rendered, commandedPwm: cmd, previewOk: false, previewAngles: [] },
        out,
      ),
    ).toBe('commanded');
    expect(out[2]).toBeCloseTo(45, 6);
    expect(out[0]).toBe(0);
  });
  it('shows a reachable preview first', () => {
    const out = new Float64Array(6);
    expect(
      ghostPose(
        {
          arm: DEMO_ARM,
          rendered,
          commandedPwm: none,
          previewOk: true,
          previewAngles: [10, 20, 30, 40],
        },
        out,
      ),
    ).toBe('preview');
    expect(Array.from(out)).toEqual([10, 20, 30, 40, 0, 0]);
  });
  it('hides the preview once the arm is there, and shows nothing before any data', () => {
    const out = new Float64Array(6);
    const there = [10, 20, 30, 40.5, 0, 0];
    expect(
      ghostPose(
        {
          arm: DEMO_ARM,
          rendered: there,
          commandedPwm: none,
          previewOk: true,
          previewAngles: [10, 20, 30, 40],
        },
        out,
      ),
    ).toBe('nothing');
    expect(
      ghostPose(
        { arm: DEMO_ARM, rendered: none, commandedPwm: none, previewOk: false, previewAngles: [] },
        out,
      ),
    ).toBe('nothing');
  });
});

describe('renderWords: where and how the 3D view is drawn (Status panel)', () => {
  const base = {
    thread: 'worker' as const,
    note: '',
    software: false,
    frameCostMs: 0,
    budget: 0.5,
  };
  it('names the thread, software WebGL and its pacing, and a fallback’s reason', () => {
    expect(renderWords(base)).toBe('Rendering: worker');
    expect(renderWords({ ...base, software: true })).toBe('Rendering: worker, software WebGL');
    expect(renderWords({ ...base, software: true, frameCostMs: 17.6 })).toBe(
      'Rendering: worker, software WebGL paced to 50 % (18 ms a frame)',
    );
    expect(renderWords({ ...base, thread: 'main', note: 'worker failed: x', software: true })).toBe(
      'Rendering: main thread (worker failed: x), software WebGL',
    );
  });
});
