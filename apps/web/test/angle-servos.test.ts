/**
 * A robot whose servo speaks angles (profile `"units": "angle"`, PROTOCOL §8): the store takes
 * `#IIIA±ddd.dd!` reports and draws the angle as it came (±360° stays ±360°), the jog slider
 * shows it, the URDF joint gets it, and jogging sends `#IIIA±ddd.ddTtttt!`. Pulse arms are
 * untouched.
 */
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterEach, beforeEach, describe, expect, it, vi } from 'vitest';
import { parseProfile, type Profile } from '@armtwin/robot';
import { encodeGroup, encodePosition } from '@armtwin/protocol';
import { ArmStore } from '../src/core/store/ArmStore.ts';
import { ArmLink } from '../src/core/link/ArmLink.ts';
import { robotSpec } from '../src/core/robots/robotSpec.ts';
import { defaultSettings } from '../src/core/config/settings.ts';
import { FakeMqttClient } from './support/FakeMqttClient.ts';

const MODELS = path.resolve(fileURLToPath(import.meta.url), '../../../../public/models');
const DEG = Math.PI / 180;

/** armtwin5 with a bus servo as wrist roll (004): ±360° of travel, in angle frames. */
function busProfile(): Profile {
  const raw = JSON.parse(
    fs.readFileSync(path.join(MODELS, 'armtwin5', 'profile.json'), 'utf8'),
  ) as {
    servos: Record<string, unknown>[];
  };
  raw.servos[4] = { ...raw.servos[4], units: 'angle', min: -360, max: 360 };
  const r = parseProfile(raw);
  if (!r.ok) throw new Error(r.errors.join('; '));
  return r.profile;
}
const SPEC = robotSpec(busProfile());

describe('ArmStore with angle reports', () => {
  it('a reported +350.00° is held, drawn and shown as 350°, and poses the URDF joint at 350°', () => {
    const store = new ArmStore({ arm: SPEC.storeArm });
    store.ingest(
      '$TIM:1700000000000!{#000P1500!#001P1600!#002P1500!#003P1500!#004A+350.00!#005P1500!}',
      0,
    );
    expect(store.angle[4]).toBe(350);
    expect(store.angle[1]).toBeCloseTo(13.5, 9);
    store.sample(1000);
    expect(store.rendered[4]).toBe(350);
    expect(store.isStale(10)).toBe(false);
    expect(store.lastStateStamp).toBe(1_700_000_000_000);
    const slider = SPEC.sliders[4]!;
    expect(slider.speaksAngle).toBe(true);
    expect(slider.valueFromAngle(store.angle[4]!)).toBe(350);
    expect(SPEC.joints.scale[4]! * store.rendered[4]! + SPEC.joints.bias[4]!).toBeCloseTo(
      350 * DEG,
      12,
    );
  });

  it("angles beyond a pulse servo's range (−359.99°) arrive whole, one frame at a time", () => {
    const store = new ArmStore({ arm: SPEC.storeArm });
    store.ingest('#004A-35', 0);
    store.ingest('9.99!', 1);
    expect(store.angle[4]).toBe(-359.99);
    // the pulse-equivalent the pulse-counting panels read is exact, not rounded nor clamped
    expect(SPEC.sliders[4]!.valueFromPwm(store.pwm[4]!)).toBeCloseTo(-359.99, 9);
  });

  it('a pulse frame and an angle frame for the same servo: the newer one is its position', () => {
    const store = new ArmStore({ arm: SPEC.storeArm });
    store.ingest('#002A+010.00!', 0);
    expect(store.angle[2]).toBe(10);
    store.ingest(encodePosition(2, 1500), 1);
    expect(store.angle[2]).toBe(0);
    expect(store.pwm[2]).toBe(1500);
    store.ingest('#002A-020.00!', 2);
    expect(store.angle[2]).toBe(-20);
  });

  it('angle moves and stray frames on the status topic say nothing about the arm', () => {
    const store = new ArmStore({ arm: SPEC.storeArm });
    store.ingest('#004A+100.00T0500!', 0);
    expect(store.angle[4]).toBeNaN();
    expect(store.counters.frames).toBe(1);
  });

  it('a pulse arm reads exactly as before', () => {
    const store = new ArmStore();
    store.ingest(encodeGroup([encodePosition(0, 1600)]), 0);
    expect(store.pwm[0]).toBe(1600);
    expect(store.angle[0]).toBeCloseTo(13.5, 9);
  });
});

/** The payloads published, on any topic. */
class FakeClient extends FakeMqttClient {
  get payloads(): string[] {
    return this.published.map((p) => p.payload);
  }
}

describe('jogging a servo that speaks angles', () => {
  beforeEach(() => vi.useFakeTimers());
  afterEach(() => vi.useRealTimers());

  it('sends angle moves within its degree limits, and pulse moves to the pulse servos', () => {
    const store = new ArmStore({ arm: SPEC.storeArm });
    const client = new FakeClient();
    const link = new ArmLink(
      store,
      defaultSettings({ protocol: 'http:', host: 'h' }),
      () => client,
    );
    link.start();
    client.emit('connect');
    const commands = () => client.payloads.filter((p) => !p.startsWith('$PNG'));
    const roll = SPEC.sliders[4]!;
    link.jog(4, roll.pwmFromValue(350));
    vi.advanceTimersByTime(60);
    link.jog(4, roll.pwmFromValue(-360));
    vi.advanceTimersByTime(60);
    link.jog(4, roll.pwmFromValue(360.5)); // beyond its limit: never sent
    vi.advanceTimersByTime(60);
    link.jog(2, SPEC.sliders[2]!.pwmFromValue(13.5));
    vi.advanceTimersByTime(60);
    expect(commands()).toEqual(['#004A+350.00T0100!', '#004A-360.00T0100!', '#002P1600T0100!']);
    // the ghost's commanded pose is the angle itself
    expect(roll.valueFromPwm(store.commandedPwm[4]!)).toBeCloseTo(-360, 9);
    link.stop();
  });
});
