import { describe, expect, it } from 'vitest';
import { GamepadJog, type GamepadEnv } from '../src/core/jog/GamepadJog.ts';
import type { HoldJog } from '../src/core/jog/HoldJog.ts';
import {
  DEFAULT_GAMEPAD_MAPPING,
  GAMEPAD_MAPPING_KEY,
  loadGamepadMapping,
  parseGamepadMapping,
  stickRate,
} from '../src/core/jog/gamepadMapping.ts';

/** Records what the gamepad asks of hold-to-jog. */
class FakeHold {
  inputs = new Map<string, { index: number; rate: number }>();
  press(name: string, index: number, rate: number) {
    this.inputs.set(name, { index, rate });
  }
  release(name: string) {
    this.inputs.delete(name);
  }
  releaseWhere(prefix: string) {
    for (const k of [...this.inputs.keys()]) if (k.startsWith(prefix)) this.inputs.delete(k);
  }
}

function pad(axes: number[], pressed: number[] = [], connected = true): Gamepad {
  const buttons = Array.from({ length: 17 }, (_, i) => ({
    pressed: pressed.includes(i),
    touched: pressed.includes(i),
    value: pressed.includes(i) ? 1 : 0,
  }));
  return { id: 'scripted', index: 0, connected, axes, buttons } as unknown as Gamepad;
}

function setup(storage?: Storage) {
  const hold = new FakeHold();
  let pads: (Gamepad | null)[] = [];
  let stops = 0;
  const env: GamepadEnv = {
    getGamepads: () => pads,
    requestAnimationFrame: () => 0,
    cancelAnimationFrame: () => {},
    addEventListener: () => {},
    removeEventListener: () => {},
    storage,
  };
  const g = new GamepadJog(hold as unknown as HoldJog, () => stops++, env);
  return { g, hold, set: (p: Gamepad | null) => (pads = [p]), stops: () => stops };
}

describe('gamepad mapping', () => {
  it('rescales a stick outside the dead zone and inverts on request', () => {
    expect(stickRate(0.1, 0.15, false)).toBe(0);
    expect(stickRate(1, 0.15, false)).toBe(1);
    expect(stickRate(-1, 0.15, true)).toBe(1);
    expect(stickRate(0.575, 0.15, false)).toBeCloseTo(0.5);
  });
  it('refuses a mapping whose enable and stop buttons are one button, or other nonsense', () => {
    expect(parseGamepadMapping({ ...DEFAULT_GAMEPAD_MAPPING, stopButton: 7 })).toEqual({
      ok: false,
      error: 'the enable and stop buttons must differ',
    });
    expect(parseGamepadMapping({ ...DEFAULT_GAMEPAD_MAPPING, deadzone: 2 }).ok).toBe(false);
    expect(
      parseGamepadMapping({
        ...DEFAULT_GAMEPAD_MAPPING,
        axes: [{ axis: 0, joint: 'w', invert: false }],
      }).ok,
    ).toBe(false);
    expect(parseGamepadMapping({ ...DEFAULT_GAMEPAD_MAPPING, axes: [{ axis: 'x' }] }).ok).toBe(
      false,
    );
    expect(parseGamepadMapping(DEFAULT_GAMEPAD_MAPPING)).toEqual({
      ok: true,
      mapping: DEFAULT_GAMEPAD_MAPPING,
    });
  });
  it('falls back to the default, saying why, when the saved mapping is bad', () => {
    const bad = { getItem: () => '{"axes":' };
    const r = loadGamepadMapping(bad);
    expect(r.mapping).toEqual(DEFAULT_GAMEPAD_MAPPING);
    expect(r.problem).toMatch(/not JSON/);
    const saved = { ...DEFAULT_GAMEPAD_MAPPING, enableButton: 6 };
    expect(
      loadGamepadMapping({
        getItem: (k) => (k === GAMEPAD_MAPPING_KEY ? JSON.stringify(saved) : null),
      }).mapping.enableButton,
    ).toBe(6);
  });
});

describe('GamepadJog', () => {
  it('jogs only while the enabling trigger is held', () => {
    const { g, hold, set } = setup();
    set(pad([1, 0, 0, 0]));
    g.poll();
    expect(hold.inputs.size).toBe(0);
    set(pad([1, 0, 0, 0], [7]));
    g.poll();
    expect(hold.inputs.get('pad:axis0')).toEqual({ index: 0, rate: 1 });
    set(pad([1, 0, 0, 0]));
    g.poll();
    expect(hold.inputs.size).toBe(0);
  });

  it('stops on the stop button and stays dead until the trigger is pressed again', () => {
    const { g, hold, set, stops } = setup();
    set(pad([0, -1, 0, 0], [7]));
    g.poll();
    expect(hold.inputs.get('pad:axis1')?.rate).toBe(1);
    set(pad([0, -1, 0, 0], [7, 1]));
    g.poll();
    expect(stops()).toBe(1);
    expect(hold.inputs.size).toBe(0);
    set(pad([0, -1, 0, 0], [7]));
    g.poll();
    expect(hold.inputs.size).toBe(0);
    set(pad([0, -1, 0, 0]));
    g.poll();
    set(pad([0, -1, 0, 0], [7]));
    g.poll();
    expect(hold.inputs.size).toBe(1);
  });

  it('lets go when the gamepad disconnects with the stick pushed', () => {
    const { g, hold, set } = setup();
    set(pad([1, 0, 0, 0], [7]));
    g.poll();
    expect(hold.inputs.size).toBe(1);
    set(null);
    g.poll();
    expect(hold.inputs.size).toBe(0);
    expect(g.state.name).toBe('');
  });

  it('drives a tip axis when the mapping says so', () => {
    const { g, hold, set } = setup();
    g.setMapping({ ...DEFAULT_GAMEPAD_MAPPING, axes: [{ axis: 1, joint: 'z', invert: true }] });
    set(pad([0, -1, 0, 0], [7]));
    g.poll();
    expect(hold.inputs.get('pad:axis1')).toEqual({ index: 'z', rate: 1 });
  });
});
