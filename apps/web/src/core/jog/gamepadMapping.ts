/**
 * A gamepad's mapping for hold-to-jog (pure): which stick axis drives which joint, the enabling
 * button that must be held for any stick to move the arm, and the emergency-stop button. Indices
 * are the browser's "standard" gamepad layout: axes 0/1 left stick x/y, 2/3 right stick x/y;
 * buttons 0 A, 1 B, 2 X, 3 Y, 4/5 shoulders, 6/7 left/right triggers. Saved in localStorage
 * as JSON; a saved mapping that does not parse is replaced by the default, with a reason.
 */
import { isTipAxis, type TipAxis } from './tipHold.ts';

export interface AxisMapping {
  /** Gamepad axis index. */
  axis: number;
  /** Joint index (servo order), `x`/`y`/`z` for the tool tip (./tipHold.ts), −1 = not used. */
  joint: number | TipAxis;
  /** Stick up / right moves the joint −. */
  invert: boolean;
}

export interface GamepadMapping {
  axes: AxisMapping[];
  /** The enabling switch: a button (or trigger) that must be held for the sticks to jog. */
  enableButton: number;
  /** The emergency stop (`#255PDST!`, as the Emergency stop button). */
  stopButton: number;
  /** Stick travel below this (0 … 1) is no input. */
  deadzone: number;
}

export const DEFAULT_GAMEPAD_MAPPING: GamepadMapping = {
  axes: [
    { axis: 0, joint: 0, invert: false },
    { axis: 1, joint: 1, invert: true },
    { axis: 3, joint: 2, invert: true },
    { axis: 2, joint: 3, invert: false },
  ],
  enableButton: 7,
  stopButton: 1,
  deadzone: 0.15,
};

/** localStorage key of the saved mapping. */
export const GAMEPAD_MAPPING_KEY = 'armtwin.gamepadMapping';

/** A trigger counts as held from this far pressed. */
export const TRIGGER_HELD = 0.5;

/** Names of the standard layout's axes and buttons, for the on-screen list. */
export const AXIS_NAMES = ['Left stick ←→', 'Left stick ↑↓', 'Right stick ←→', 'Right stick ↑↓'];
export const BUTTON_NAMES = [
  'A / ✕',
  'B / ○',
  'X / □',
  'Y / △',
  'Left shoulder',
  'Right shoulder',
  'Left trigger',
  'Right trigger',
  'Back',
  'Start',
  'Left stick press',
  'Right stick press',
  'D-pad ↑',
  'D-pad ↓',
  'D-pad ←',
  'D-pad →',
];

const isIndex = (v: unknown, max: number): v is number =>
  typeof v === 'number' && Number.isInteger(v) && v >= 0 && v < max;

export type MappingParse = { ok: true; mapping: GamepadMapping } | { ok: false; error: string };

/** Checks a mapping (parsed JSON): the enable and stop buttons must differ. */
export function parseGamepadMapping(value: unknown): MappingParse {
  const bad = (error: string): MappingParse => ({ ok: false, error });
  if (typeof value !== 'object' || value === null) return bad('not an object');
  const v = value as Record<string, unknown>;
  if (!Array.isArray(v.axes) || v.axes.length > 16) return bad('axes: a list of at most 16');
  const axes: AxisMapping[] = [];
  for (const [i, a] of v.axes.entries()) {
    const m = a as Record<string, unknown> | null;
    if (typeof m !== 'object' || m === null) return bad(`axes[${i}]: not an object`);
    if (!isIndex(m.axis, 16)) return bad(`axes[${i}].axis: an index 0–15`);
    if (!(m.joint === -1 || isIndex(m.joint, 32) || isTipAxis(m.joint)))
      return bad(`axes[${i}].joint: −1, 0–31, x, y or z`);
    if (typeof m.invert !== 'boolean') return bad(`axes[${i}].invert: true or false`);
    axes.push({ axis: m.axis, joint: m.joint as number | TipAxis, invert: m.invert });
  }
  if (!isIndex(v.enableButton, 32)) return bad('enableButton: an index 0–31');
  if (!isIndex(v.stopButton, 32)) return bad('stopButton: an index 0–31');
  if (v.enableButton === v.stopButton) return bad('the enable and stop buttons must differ');
  const dz = v.deadzone;
  if (typeof dz !== 'number' || !(dz >= 0 && dz < 1)) return bad('deadzone: 0 to under 1');
  return {
    ok: true,
    mapping: { axes, enableButton: v.enableButton, stopButton: v.stopButton, deadzone: dz },
  };
}

/** The saved mapping, or the default (with why) when none is saved or it does not parse. */
export function loadGamepadMapping(storage: Pick<Storage, 'getItem'> | undefined): {
  mapping: GamepadMapping;
  problem: string;
} {
  const fallback = { mapping: structuredClone(DEFAULT_GAMEPAD_MAPPING), problem: '' };
  const text = storage?.getItem(GAMEPAD_MAPPING_KEY);
  if (!text) return fallback;
  let json: unknown;
  try {
    json = JSON.parse(text);
  } catch {
    return { ...fallback, problem: 'The saved gamepad mapping is not JSON: default used.' };
  }
  const r = parseGamepadMapping(json);
  return r.ok
    ? { mapping: r.mapping, problem: '' }
    : { ...fallback, problem: `The saved gamepad mapping was refused (${r.error}): default used.` };
}

/** The stick rate of one axis value: 0 inside the dead zone, else rescaled to 0 … ±1. */
export function stickRate(value: number, deadzone: number, invert: boolean): number {
  if (!Number.isFinite(value) || Math.abs(value) < deadzone) return 0;
  const r = (Math.sign(value) * (Math.min(1, Math.abs(value)) - deadzone)) / (1 - deadzone);
  return invert ? -r : r;
}
