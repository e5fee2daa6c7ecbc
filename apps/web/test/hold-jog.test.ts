import { describe, expect, it } from 'vitest';
import { encodeGroup, encodePosition } from '@armtwin/protocol';
import { ArmStore } from '../src/core/store/ArmStore.ts';
import { ArmLink } from '../src/core/link/ArmLink.ts';
import { FakeMqttClient } from './support/FakeMqttClient.ts';
import { defaultSettings } from '../src/core/config/settings.ts';
import { robotSpec } from '../src/core/robots/robotSpec.ts';
import { DEFAULT_PROFILE } from '../src/core/robots/defaultProfile.ts';
import { HoldJog } from '../src/core/jog/HoldJog.ts';
import { createMotionRobot, tipPose } from '@armtwin/motion';
import { solveIk } from '@armtwin/ik';
import { parseProfile } from '@armtwin/robot';
import { TargetPreview } from '../src/core/store/TargetPreview.ts';
import armtwin5 from '../../../public/models/armtwin5/profile.json';
import {
  combinedRate,
  holdTarget,
  keyHold,
  DEFAULT_HOLD_KEYS,
} from '../src/core/jog/holdJogMath.ts';

/** The control payloads published (no pings). */
class FakeClient extends FakeMqttClient {
  get controls(): string[] {
    return this.published
      .filter((p) => !p.payload.startsWith('$PNG') && p.topic.endsWith('/control'))
      .map((p) => p.payload);
  }
}

/** A connected link to the 5-axis demo arm at home (1500 µs), a HoldJog whose ticks the test runs. */
function setup(withMotion = false, motion = createMotionRobot(DEFAULT_PROFILE)) {
  const store = new ArmStore();
  const client = new FakeClient();
  const link = new ArmLink(store, defaultSettings({ protocol: 'http:', host: 'h' }), () => client);
  link.start();
  client.emit('connect');
  const report = (pwm: number[]) =>
    client.emit(
      'message',
      'arm/arm1/status',
      new TextEncoder().encode(encodeGroup(pwm.map((p, i) => encodePosition(i, p)))),
    );
  report([1500, 1500, 1500, 1500, 1500, 1500]);
  const spec = robotSpec(DEFAULT_PROFILE);
  const ghost = new TargetPreview();
  let tickFn: (() => void) | null = null;
  const hold = new HoldJog({
    store,
    link: () => link,
    robot: () => ({ sliders: spec.sliders, motion: withMotion ? motion : null }),
    ghost,
    timers: {
      setInterval: (fn) => ((tickFn = fn), 1),
      clearInterval: () => (tickFn = null),
    },
  });
  const tick = () => tickFn?.();
  return {
    store,
    client,
    link,
    hold,
    report,
    tick,
    motion,
    spec,
    ghost,
    ticking: () => tickFn !== null,
  };
}

describe('hold-to-jog arithmetic', () => {
  it('aims one horizon ahead at the chosen speed, within the limits', () => {
    expect(holdTarget(10, 1, 20, 250, -90, 90)).toBe(15);
    expect(holdTarget(10, -0.5, 20, 250, -90, 90)).toBe(7.5);
    expect(holdTarget(89, 1, 20, 250, -90, 90)).toBe(90);
    expect(holdTarget(NaN, 1, 20, 250, -90, 90)).toBeNaN();
  });
  it('adds the inputs on one joint within ±1, and maps keys to joints', () => {
    expect(combinedRate([1, 1])).toBe(1);
    expect(combinedRate([1, -1])).toBe(0);
    expect(keyHold(DEFAULT_HOLD_KEYS, 'KeyW')).toEqual({ index: 1, rate: 1 });
    expect(keyHold(DEFAULT_HOLD_KEYS, 'KeyS')).toEqual({ index: 1, rate: -1 });
    expect(keyHold(DEFAULT_HOLD_KEYS, 'KeyZ')).toBeNull();
  });
});

describe('HoldJog', () => {
  it('sends a short move at once and every keep-alive, and a per-servo stop on release', () => {
    const { client, hold, tick, ticking } = setup();
    hold.speed = 20;
    hold.press('key:KeyW', 1, 1);
    // 20 °/s × 250 ms = 5° ahead of home, in 250 ms
    expect(client.controls).toHaveLength(1);
    expect(client.controls[0]).toMatch(/^#001P\d{4}T0250!$/);
    const first = Number(client.controls[0]!.slice(5, 9));
    expect(first).toBeGreaterThan(1500);
    tick();
    expect(client.controls).toHaveLength(2);
    hold.release('key:KeyW');
    expect(client.controls.at(-1)).toBe('#001PDST!');
    expect(ticking()).toBe(false);
  });

  it('groups several held joints into one command, and stops only the joint let go', () => {
    const { client, hold, tick } = setup();
    hold.press('a', 0, 1);
    hold.press('b', 2, -1);
    tick();
    expect(client.controls.at(-1)).toMatch(/^\{#000P\d{4}T0250!#002P\d{4}T0250!\}$/);
    hold.release('a');
    expect(client.controls.at(-1)).toBe('#000PDST!');
    tick();
    expect(client.controls.at(-1)).toMatch(/^#002P\d{4}T0250!$/);
  });

  it('lets go of everything on the emergency stop without sending stops of its own', () => {
    const { client, hold, link, ticking } = setup();
    link.stopListeners.add(() => hold.releaseAll(false));
    hold.press('pad:axis0', 0, 0.5);
    link.emergencyStop();
    expect(client.controls.at(-1)).toBe('#255PDST!');
    expect(hold.held()).toEqual([]);
    expect(ticking()).toBe(false);
  });

  it('stops and says why when the data goes stale mid-hold', () => {
    const { client, hold, tick, store } = setup();
    hold.press('k', 1, 1);
    store.connection = 'reconnecting';
    tick();
    expect(client.controls.at(-1)).toBe('#001PDST!');
    expect(hold.refusal).toMatch(/Stopped/);
    expect(hold.held()).toEqual([]);
  });

  it('does not start a hold while the link cannot command', () => {
    const { client, hold, store } = setup();
    store.connection = 'reconnecting';
    hold.press('k', 1, 1);
    expect(client.controls).toEqual([]);
  });

  it('moves the tip up along z through the IK, pitch kept, and stops every servo it moved', () => {
    const { client, hold, report, motion } = setup(true);
    const spec = robotSpec(DEFAULT_PROFILE);
    // a pose the IK itself chose, tip at (250, 0, 200) pointing level
    const ik = solveIk(250, 0, 200, 0, spec.storeArm);
    const bent = [...ik.pwm.slice(0, 4), 1500, 1500];
    report(bent);
    hold.setSpeed(60);
    hold.press('t', 'z', 1);
    const sent = client.controls.at(-1)!;
    expect(sent).toMatch(/^\{(#00[0-3]P\d{4}T0250!)+\}$/);
    const to = [...bent];
    for (const m of sent.matchAll(/#00(\d)P(\d{4})T/g)) to[Number(m[1])] = Number(m[2]);
    const a = tipPose(motion, bent);
    const b = tipPose(motion, to);
    expect(b.z - a.z).toBeGreaterThan(10); // 60 mm/s × 250 ms = 15 mm (pulses are whole µs)
    expect(Math.abs(b.x - a.x)).toBeLessThan(2);
    expect(Math.abs(b.pitch - a.pitch)).toBeLessThan(1);
    hold.release('t');
    expect(client.controls.at(-1)).toMatch(/^(#00[0-3]PDST!)+$/);
    expect(hold.held()).toEqual([]);
  });

  it('stops and says why when the tip cannot go further', () => {
    const { client, hold } = setup(true); // at home the arm points straight up: no higher
    hold.press('t', 'z', 1);
    expect(hold.refusal).toMatch(/^Stopped: /);
    expect(hold.held()).toEqual([]);
    expect(client.controls.filter((p) => !p.includes('PDST'))).toEqual([]);
  });

  it('stops rather than turn a joint fast near a singularity', () => {
    const { client, hold, report } = setup(true);
    // nearly stretched out: 15 mm up needs the elbow to turn about 20°
    const ik = solveIk(200, 0, 150, -45, robotSpec(DEFAULT_PROFILE).storeArm);
    report([...ik.pwm.slice(0, 4), 1500, 1500]);
    hold.setSpeed(60);
    hold.press('t', 'z', 1);
    expect(hold.refusal).toMatch(/^Stopped: moving the tip would turn Elbow \d+° at once/);
    expect(client.controls.filter((p) => !p.includes('PDST'))).toEqual([]);
  });
});

/** A table in front of the arm, its top 30 mm above the floor (tests/e2e/keep-out-zones.spec.ts). */
const TABLE = { name: 'table', shape: 'box', min: [150, -150, -20], max: [400, 150, 30] };

function withTable() {
  const parsed = parseProfile({ ...armtwin5, keepOut: { zones: [TABLE] } });
  if (!parsed.ok) throw new Error(parsed.errors.join('\n'));
  const s = setup(true, createMotionRobot(parsed.profile));
  const joint = (name: string) => s.spec.sliders.findIndex((j) => j.name === name);
  // Upper arm at 45°, forearm level: clear of the table.
  const at = [1500, 1500, 1500, 1500, 1500, 1500];
  for (const name of ['Shoulder', 'Elbow'])
    at[joint(name)] = s.spec.sliders[joint(name)]!.pwmFromValue(-45);
  s.report(at);
  return { ...s, joint };
}

describe('a slider move: a hold of one target', () => {
  it('is sent through the link (coalesced to one move per servo), the ghost cleared', () => {
    const { client, hold, joint, spec, ghost, store } = withTable();
    ghost.refuse([0, 0, 0, 0, 0], 'wrist_pitch');
    const i = joint('Wrist pitch');
    expect(hold.jogTo(i, spec.sliders[i]!.pwmFromValue(-10))).toBe('');
    expect(ghost.refused).toBe(false);
    expect(store.commandedPwm[spec.sliders[i]!.id]).toBe(spec.sliders[i]!.pwmFromValue(-10));
    expect(client.controls.at(-1)).toMatch(/^#003P\d{4}T\d{4}!$/);
  });

  it('into a keep-out zone is not sent, says why, and the ghost shows it with the hand red', () => {
    const { client, hold, joint, spec, ghost } = withTable();
    const sent = client.controls.length;
    const i = joint('Wrist pitch');
    // The hand pointing down from there would go into the table.
    expect(hold.jogTo(i, spec.sliders[i]!.pwmFromValue(-90))).toMatch(
      /^Not sent: hand \d+\.\d mm into zone "table"\.$/,
    );
    expect(client.controls).toHaveLength(sent);
    expect(ghost.refused).toBe(true);
    expect(ghost.refusedJoint).toBe('wrist_pitch');
  });

  it('and a held joint meet the same check: the hold stops short of the table', () => {
    const { client, hold, joint, spec, report, store } = withTable();
    const i = joint('Wrist pitch');
    const near = Array.from(store.pwm);
    near[i] = spec.sliders[i]!.pwmFromValue(-85);
    report(near);
    expect(hold.jogTo(i, near[i]!)).toBe(''); // clear where it is
    const sent = client.controls.length;
    hold.speed = 60;
    hold.press('k', i, -1);
    // No move towards the table went out, only the stop of the joint it held.
    expect(client.controls.slice(sent)).toEqual(['#003PDST!']);
    expect(hold.refusal).toMatch(/^Stopped: hand \d+\.\d mm into zone "table"\.$/);
  });
});
