/**
 * Hold-to-jog: joints move only while an input holds them (a − / + button under a pointer or a
 * finger, a hold key, a gamepad stick with its enabling trigger). Each input is named (e.g.
 * `pointer:2`, `key:KeyQ`, `pad:axis1`) and gives a target, a joint index or a tip axis
 * (`x`, `y`, `z`: ./tipHold.ts), and a rate (−1 … 1). While anything is held, a keep-alive goes
 * out every `keepAliveMs` (./holdJogMath.ts); when a joint's last input lets go, `#IIIPDST!` goes
 * out for it at once (for a tip axis, for every servo the tip moves). While a tip axis is held,
 * held joints wait. Everything lets go when the window loses
 * focus or is hidden, on the emergency stop (which then sends only its own `#255PDST!`), when
 * the link cannot command, and when a keep-alive would take the hand below the floor.
 * Timers are the main thread's on purpose: a stalled page sends no keep-alive, and the arm stops
 * at the end of the last short move.
 */
import type { MotionRobot } from '@armtwin/motion';
import { angleFromPwm } from '@armtwin/protocol';
import { jogRefusal } from './keepOut.ts';
import type { ArmStore } from '../store/ArmStore.ts';
import type { ArmCommands } from '../link/ArmCommands.ts';
import type { SliderSpec } from '../robots/robotSpec.ts';
import { isTipAxis, tipHold, type TipAxis } from './tipHold.ts';
import {
  combinedRate,
  DEFAULT_HOLD_JOG_OPTIONS,
  DEFAULT_HOLD_KEYS,
  holdTarget,
  keyHold,
  type HoldJogOptions,
  type HoldKeys,
} from './holdJogMath.ts';

/** Whether a key goes to a text field (then it types, it does not jog). */
const isTyping = (t: EventTarget | null): boolean => {
  const el = t as HTMLElement | null;
  if (!el || typeof el.tagName !== 'string') return false;
  if (el.isContentEditable || el.tagName === 'TEXTAREA' || el.tagName === 'SELECT') return true;
  return (
    el.tagName === 'INPUT' &&
    !['range', 'checkbox', 'radio', 'button'].includes((el as HTMLInputElement).type)
  );
};

/**
 * What jogging needs of the arm link (../link/ArmLink.ts); without `mayMove`, `command` decides
 * whether this page may move the arm.
 */
export type HoldLink = Pick<ArmCommands, 'jog' | 'holdMoves' | 'stopServos'> & {
  readonly permissions: { readonly command: boolean };
  readonly mayMove?: boolean;
};

export interface HoldJogDeps {
  store: ArmStore;
  /** The current link (it is replaced on reconnect). */
  link(): HoldLink;
  /** The active robot's joints and planner model. */
  robot(): { sliders: readonly SliderSpec[]; motion: MotionRobot | null };
  /** Where a refused slider move is shown: the ghost, in the pose it would have reached. */
  ghost?: RefusedPose;
  timers?: {
    setInterval(fn: () => void, ms: number): unknown;
    clearInterval(h: unknown): void;
  };
  now?: () => number;
}

/** The ghost's side of a refused jog (../store/TargetPreview.ts). */
export interface RefusedPose {
  refuse(angles: ArrayLike<number>, joint: string): void;
  clearRefused(): void;
}

/** What an input holds: a joint (its index in servo order) or an axis of the tool tip. */
export type JogTarget = number | TipAxis;

interface Input {
  index: JogTarget;
  rate: number;
}

export class HoldJog {
  readonly opts: HoldJogOptions;
  /** Joint units per second. */
  speed: number;
  /** Why the last hold was cut short ('' = it was not). */
  refusal = '';
  private readonly inputs = new Map<string, Input>();
  /** Joints a keep-alive went out for and no stop yet, by index → wire id. */
  private readonly moving = new Map<number, { id: number; by: 'joint' | 'tip' }>();
  private timer: unknown = undefined;
  private readonly timers: NonNullable<HoldJogDeps['timers']>;
  private readonly now: () => number;
  private readonly listeners = new Set<() => void>();

  constructor(
    private readonly deps: HoldJogDeps,
    opts: Partial<HoldJogOptions> = {},
  ) {
    this.opts = { ...DEFAULT_HOLD_JOG_OPTIONS, ...opts };
    this.speed = this.opts.speed;
    this.timers = deps.timers ?? {
      setInterval: (fn, ms) => setInterval(fn, ms),
      clearInterval: (h) => clearInterval(h as ReturnType<typeof setInterval>),
    };
    this.now = deps.now ?? (() => performance.now());
  }

  /** Sets the speed, joint units per second (one of `opts.speeds`, or any positive number). */
  setSpeed(speed: number): void {
    if (Number.isFinite(speed) && speed > 0) this.speed = speed;
  }

  /** Called when what the panel shows changes (held joints, refusal). */
  onChange(fn: () => void): () => void {
    this.listeners.add(fn);
    return () => this.listeners.delete(fn);
  }

  /** Joint indices and tip axes held now. */
  held(): JogTarget[] {
    return [...new Set([...this.inputs.values()].filter((i) => i.rate !== 0).map((i) => i.index))];
  }

  /** Whether joints may be held now (connected, fresh data, a role that commands). */
  canHold(): boolean {
    const { store } = this.deps;
    const link = this.deps.link();
    return (
      (link.mayMove ?? link.permissions.command) &&
      store.connection === 'connected' &&
      !store.isStale(this.now())
    );
  }

  /**
   * Input `name` holds joint `index` at `rate` (−1 … 1; 0 lets go). A joint that starts moving
   * gets its first keep-alive at once.
   */
  press(name: string, index: JogTarget, rate: number): void {
    if (rate === 0 || !Number.isFinite(rate)) return this.release(name);
    const before = this.inputs.get(name);
    if (before && before.index === index && before.rate === rate) return;
    if (!this.canHold()) return;
    const wasHeld = this.held().includes(index);
    if (before && before.index !== index) this.release(name);
    this.inputs.set(name, { index, rate });
    if (!wasHeld) {
      this.refusal = '';
      this.tick();
      this.emit();
    }
    if (this.timer === undefined && this.inputs.size > 0)
      this.timer = this.timers.setInterval(() => this.tick(), this.opts.keepAliveMs);
  }

  /**
   * A slider moved joint `index` to `pulse`: a hold of one target, checked as every keep-alive
   * is (the one keep-out check, ./keepOut.ts) and sent through the link's coalescer. Returns
   * '' when sent, else why not (the ghost then shows the refused pose, its colliding link red).
   */
  jogTo(index: number, pulse: number): string {
    const spec = this.deps.robot().sliders[index];
    if (!spec) return '';
    const { store } = this.deps;
    const from = Array.from(store.pwm);
    const to = [...from];
    to[index] = pulse;
    const refused = jogRefusal(this.deps.robot().motion, from, to);
    if (refused) {
      const servos = store.opts.arm.servos;
      if (refused.joint)
        this.deps.ghost?.refuse(
          to.map((p, k) => angleFromPwm(p, servos[k]?.polarity ?? 1)),
          refused.joint,
        );
      return `Not sent: ${refused.message}.`;
    }
    this.deps.ghost?.clearRefused();
    this.deps.link().jog(spec.id, pulse);
    return '';
  }

  /** Input `name` lets go: a joint no input holds any more is stopped at once. */
  release(name: string): void {
    if (!this.inputs.delete(name)) return;
    this.stopUnheld();
    this.emit();
  }

  /** Every input whose name starts with `prefix` lets go (e.g. `pad:` when a gamepad goes). */
  releaseWhere(prefix: string): void {
    let any = false;
    for (const name of [...this.inputs.keys()])
      if (name.startsWith(prefix)) any = this.inputs.delete(name) || any;
    if (!any) return;
    this.stopUnheld();
    this.emit();
  }

  /**
   * Everything lets go (blur, hidden page, lost link). `sendStops` false: the caller stops the
   * arm itself (the emergency stop's `#255PDST!`).
   */
  releaseAll(sendStops = true): void {
    this.inputs.clear();
    this.clearTimer();
    if (sendStops) this.stopUnheld();
    else this.moving.clear();
    this.emit();
  }

  /**
   * Listens to the page: hold keys (`keys`, not while typing in a field, not with Ctrl/Alt/Meta),
   * and lets go of everything on blur, pagehide and a hidden page. Returns the detach.
   */
  attach(win: Window, doc: Document, keys: HoldKeys = DEFAULT_HOLD_KEYS): () => void {
    const letGo = () => this.releaseAll();
    const onVisibility = () => doc.visibilityState === 'hidden' && this.releaseAll();
    const onKeyDown = (e: KeyboardEvent) => {
      const k = keyHold(keys, e.code);
      if (!k || e.ctrlKey || e.altKey || e.metaKey || isTyping(e.target)) return;
      e.preventDefault();
      if (!e.repeat) this.press(`key:${e.code}`, k.index, k.rate);
    };
    const onKeyUp = (e: KeyboardEvent) => this.release(`key:${e.code}`);
    win.addEventListener('keydown', onKeyDown);
    win.addEventListener('keyup', onKeyUp);
    win.addEventListener('blur', letGo);
    win.addEventListener('pagehide', letGo);
    doc.addEventListener('visibilitychange', onVisibility);
    return () => {
      win.removeEventListener('keydown', onKeyDown);
      win.removeEventListener('keyup', onKeyUp);
      win.removeEventListener('blur', letGo);
      win.removeEventListener('pagehide', letGo);
      doc.removeEventListener('visibilitychange', onVisibility);
    };
  }

  private clearTimer(): void {
    if (this.timer !== undefined) this.timers.clearInterval(this.timer);
    this.timer = undefined;
  }

  private stopUnheld(): void {
    const held = new Set(this.held());
    const tipHeld = [...held].some(isTipAxis);
    const ids: number[] = [];
    for (const [index, m] of this.moving)
      if (m.by === 'joint' ? !held.has(index) || tipHeld : !tipHeld) {
        ids.push(m.id);
        this.moving.delete(index);
      }
    if (ids.length > 0) this.deps.link().stopServos(ids);
    if (this.inputs.size === 0) this.clearTimer();
  }

  private refuse(message: string): void {
    this.refusal = message;
    this.releaseAll();
  }

  /** One keep-alive for every held joint. */
  private tick(): void {
    if (this.inputs.size === 0) return this.clearTimer();
    if (!this.canHold()) return this.refuse('Stopped: the link cannot command or data is stale.');
    const { store } = this.deps;
    const { sliders, motion } = this.deps.robot();
    const rates = new Map<JogTarget, number[]>();
    for (const { index, rate } of this.inputs.values())
      rates.set(index, [...(rates.get(index) ?? []), rate]);
    const from = Array.from(store.pwm);
    const to = [...from];
    const moves: [number, number][] = [];
    const tip = { x: 0, y: 0, z: 0 };
    for (const [target, rs] of rates) if (isTipAxis(target)) tip[target] = combinedRate(rs);
    if (tip.x !== 0 || tip.y !== 0 || tip.z !== 0) {
      if (!motion) return this.refuse('Stopped: no planner model for this arm to move the tip.');
      const r = tipHold(motion, store.opts.arm, from, tip, this.speed, this.opts.horizonMs);
      if (!r.ok) return this.refuse(`Stopped: ${r.message}.`);
      for (const [index, pwm] of r.pwm.entries()) {
        const spec = sliders[index];
        if (!spec || !Number.isFinite(pwm)) continue;
        const step = Math.abs(spec.valueFromPwm(pwm) - spec.valueFromPwm(from[index]!));
        if (step > this.opts.maxTipJointStep)
          return this.refuse(
            `Stopped: moving the tip would turn ${spec.name} ${step.toFixed(0)}${spec.unit === 'deg' ? '°' : ' mm'} at once (the IK's pose is far from the arm's); jog the joints instead`,
          );
      }
      r.pwm.forEach((pwm, index) => {
        const id = sliders[index]?.id;
        if (id === undefined || !Number.isFinite(pwm)) return;
        to[index] = pwm;
        moves.push([id, pwm]);
        this.moving.set(index, { id, by: 'tip' });
      });
      rates.clear(); // held joints wait while the tip moves
    }
    for (const [index, rs] of rates) {
      if (isTipAxis(index)) continue;
      const spec = sliders[index];
      const rate = combinedRate(rs);
      if (!spec || rate === 0) continue;
      const live = spec.speaksAngle
        ? spec.valueFromAngle(store.angle[index]!)
        : spec.valueFromPwm(store.pwm[index]!);
      const value = holdTarget(live, rate, this.speed, this.opts.horizonMs, spec.min, spec.max);
      if (Number.isNaN(value)) continue;
      const pwm = spec.pwmFromValue(value);
      to[index] = pwm;
      moves.push([spec.id, pwm]);
      this.moving.set(index, { id: spec.id, by: 'joint' });
    }
    if (moves.length === 0) return;
    const refused = jogRefusal(motion, from, to);
    if (refused) return this.refuse(`Stopped: ${refused.message}.`);
    if (!this.deps.link().holdMoves(moves, this.opts.horizonMs))
      this.refuse('Stopped: the move was not sent.');
  }

  private emit(): void {
    for (const fn of this.listeners) fn();
  }
}
