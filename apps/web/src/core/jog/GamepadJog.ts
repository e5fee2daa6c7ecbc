/**
 * Gamepads (the browser Gamepad API) for hold-to-jog: polled every animation frame (never
 * through React state). With the mapping's enabling button held, each mapped stick holds its
 * joint (inputs `pad:axisN` of ./HoldJog.ts) at the stick's rate; letting go of the enabling
 * button lets go of every stick at once. The stop button sends the emergency stop; after it the
 * sticks stay dead until the enabling button is released and pressed again. A gamepad that
 * disconnects (or vanishes from `getGamepads()`) lets go of its sticks at once.
 */
import type { HoldJog } from './HoldJog.ts';
import {
  loadGamepadMapping,
  stickRate,
  TRIGGER_HELD,
  GAMEPAD_MAPPING_KEY,
  type GamepadMapping,
} from './gamepadMapping.ts';

export interface GamepadEnv {
  getGamepads(): ReadonlyArray<Gamepad | null>;
  requestAnimationFrame(fn: () => void): number;
  cancelAnimationFrame(h: number): void;
  addEventListener(type: string, fn: (e: Event) => void): void;
  removeEventListener(type: string, fn: (e: Event) => void): void;
  storage?: Storage;
}

/** What the Jog panel shows of the gamepad (sampled). */
export interface GamepadState {
  /** The gamepad in use ('' = none). */
  name: string;
  enabled: boolean;
  /** The sticks are dead after a stop until the enabling button is pressed again. */
  latched: boolean;
  lastStop: string;
}

const pressed = (b: GamepadButton | undefined) =>
  Boolean(b && (b.pressed || b.value >= TRIGGER_HELD));

export class GamepadJog {
  mapping: GamepadMapping;
  /** Why the saved mapping was not used ('' = it was, or none was saved). */
  mappingProblem: string;
  readonly state: GamepadState = { name: '', enabled: false, latched: false, lastStop: '' };
  private padIndex = -1;
  private stopWasDown = false;
  private raf = 0;
  private running = false;

  constructor(
    private readonly hold: HoldJog,
    private readonly emergencyStop: () => void,
    private readonly env: GamepadEnv,
  ) {
    const loaded = loadGamepadMapping(env.storage);
    this.mapping = loaded.mapping;
    this.mappingProblem = loaded.problem;
  }

  /** Uses and saves a new mapping (already checked); the sticks let go first. */
  setMapping(m: GamepadMapping): void {
    this.hold.releaseWhere('pad:');
    this.mapping = m;
    this.mappingProblem = '';
    try {
      this.env.storage?.setItem(GAMEPAD_MAPPING_KEY, JSON.stringify(m));
    } catch {
      // storage full or denied: the mapping holds for this page
    }
  }

  start(): void {
    if (this.running) return;
    this.running = true;
    this.env.addEventListener('gamepadconnected', this.onConnect);
    this.env.addEventListener('gamepaddisconnected', this.onDisconnect);
    this.raf = this.env.requestAnimationFrame(this.frame);
  }

  stop(): void {
    this.running = false;
    this.env.cancelAnimationFrame(this.raf);
    this.env.removeEventListener('gamepadconnected', this.onConnect);
    this.env.removeEventListener('gamepaddisconnected', this.onDisconnect);
    this.letGo();
  }

  private readonly onConnect = (e: Event) => {
    const pad = (e as GamepadEvent).gamepad;
    if (this.padIndex < 0 && pad) this.padIndex = pad.index;
  };

  private readonly onDisconnect = (e: Event) => {
    const pad = (e as GamepadEvent).gamepad;
    if (!pad || pad.index === this.padIndex) this.lost();
  };

  private readonly frame = () => {
    if (!this.running) return;
    this.poll();
    this.raf = this.env.requestAnimationFrame(this.frame);
  };

  private lost(): void {
    this.padIndex = -1;
    this.state.name = '';
    this.letGo();
  }

  private letGo(): void {
    this.state.enabled = false;
    this.hold.releaseWhere('pad:');
  }

  /** One look at the gamepad (each animation frame). */
  poll(): void {
    let pads: ReadonlyArray<Gamepad | null>;
    try {
      pads = this.env.getGamepads();
    } catch {
      pads = [];
    }
    let pad = this.padIndex >= 0 ? pads[this.padIndex] : null;
    if (!pad || !pad.connected) {
      if (this.padIndex >= 0) this.lost();
      pad = pads.find((p) => p?.connected) ?? null;
      if (!pad) return;
      this.padIndex = pad.index;
    }
    this.state.name = pad.id || `gamepad ${pad.index}`;
    const m = this.mapping;
    const stopDown = pressed(pad.buttons[m.stopButton]);
    if (stopDown && !this.stopWasDown) {
      this.state.latched = true;
      this.letGo();
      this.emergencyStop();
      this.state.lastStop = new Date().toLocaleTimeString();
    }
    this.stopWasDown = stopDown;
    const enabled = pressed(pad.buttons[m.enableButton]);
    if (!enabled) {
      this.state.latched = false;
      if (this.state.enabled) this.letGo();
      return;
    }
    if (this.state.latched || stopDown) return;
    this.state.enabled = true;
    for (const a of m.axes) {
      const name = `pad:axis${a.axis}`;
      const rate = a.joint === -1 ? 0 : stickRate(pad.axes[a.axis] ?? 0, m.deadzone, a.invert);
      if (rate === 0) this.hold.release(name);
      else this.hold.press(name, a.joint, rate);
    }
  }
}
