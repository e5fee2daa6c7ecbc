/**
 * The page's Model / Shadow / Twin state (../link/modes.ts) as a plain object: the mode of each arm
 * (kept in the URL's `?mode=` for the selected arm and in sessionStorage per arm), the model
 * copy's store (its status, drawn beside the arm), and the switch itself: it tells the arm link
 * (which routes every command by it, ../link/ArmLink.ts) and, into Model, asks `armtwin up` to
 * start the copy at the real arm's pose. Leaving Model leaves the copy running: the server stops
 * it once idle (docs/protocol.md § Modes). Panels sample `mode`, `note`.
 */
import { ArmStore } from '../store/ArmStore.ts';
import type { HudSettings } from '../config/settings.ts';
import { defaultMode, modelArmId, parseMode, type ArmMode } from '../link/modes.ts';
import { poseBody, startModelCopy, type ModelCopyResult } from './modelCopy.ts';

export interface ModeSwitchDeps {
  /** The page's address (the `?mode=` is read from it and written back). */
  location: { search: string; pathname: string; hash: string };
  replaceUrl(url: string): void;
  storage: Pick<Storage, 'getItem' | 'setItem'> | null;
  startCopy?: typeof startModelCopy;
}

/** What the switch needs of the arm link (../link/ArmLink.ts), which routes commands by the mode. */
export interface ModeLink {
  readonly settings: HudSettings;
  readonly permissions: { readonly command: boolean };
  setMode(mode: ArmMode, copy: ArmStore | null): void;
}

const storageKey = (armId: string) => `armtwin.mode.${armId}`;

/** The query string with `mode` set (other parameters kept). Pure. */
export function queryWithMode(search: string, mode: ArmMode): string {
  const q = new URLSearchParams(search);
  q.set('mode', mode);
  return `?${q.toString()}`;
}

export class ModeSwitch {
  /** The selected arm's mode; null until it is known (the role decides the default). */
  mode: ArmMode | null = null;
  /** The model copy's status (Model mode): drawn as the sibling, and a rehearsal runs on it. */
  readonly copy = new ArmStore({ twinMode: 'newest' });
  /** What the page says about the copy ('' = nothing): starting, started, or why not. */
  note = '';
  noteBad = false;
  /** Bumped at every switch (the Plan panel keeps a rehearsal only for the mode it ran in). */
  version = 0;
  private link: ModeLink | null = null;
  private store: ArmStore | null = null;
  constructor(private readonly deps: ModeSwitchDeps) {}

  /**
   * The mode a page opens the arm in: the one chosen for it in this tab, else the address's
   * `?mode=`, else by the role (Twin for a role that may drive, Shadow for a viewer). Only a
   * choice is remembered: a viewer's Shadow does not stick once an operator logs in.
   */
  initial(armId: string, mayCommand: boolean): ArmMode {
    const saved = parseMode(this.deps.storage?.getItem(storageKey(armId)));
    const asked = parseMode(new URLSearchParams(this.deps.location.search).get('mode'));
    return saved ?? asked ?? defaultMode(mayCommand);
  }

  /**
   * A new arm link (page start, another arm, a reconnect), once the role is known: the arm's
   * mode is applied to it.
   */
  attach(link: ModeLink, store: ArmStore): void {
    this.link = link;
    this.store = store;
    this.mode = null;
    this.set(this.initial(link.settings.armId, link.permissions.command), false);
  }

  /** The store the page's commands act on now: the copy's in Model mode, else the arm's. */
  driven(store: ArmStore): ArmStore {
    return this.mode === 'model' ? this.copy : store;
  }

  /** `chosen`: the user's choice (kept for this arm in the tab and the address). */
  set(mode: ArmMode, chosen = true): void {
    const link = this.link;
    const store = this.store;
    if (!link || !store || mode === this.mode) return;
    const armId = link.settings.armId;
    if (mode === 'model' && !modelArmId(armId)) return; // a copy has no copy (ModeBar says so)
    if (mode === 'model') {
      this.copy.configure(store.opts.arm);
      this.note = 'Starting the model copy…';
      this.noteBad = false;
      void this.startCopy(link, store);
    } else {
      this.note = '';
    }
    link.setMode(mode, this.copy);
    this.mode = mode;
    this.version++;
    if (!chosen) return;
    this.deps.storage?.setItem(storageKey(armId), mode);
    const { pathname, search, hash } = this.deps.location;
    this.deps.replaceUrl(`${pathname}${queryWithMode(search, mode)}${hash}`);
  }

  /** The copy at the real arm's last reported pose (retried while none is known yet, ≤ 5 s). */
  private async startCopy(link: ModeLink, store: ArmStore): Promise<void> {
    const ids = store.opts.arm.servos.map((s) => s.id);
    let pulses = poseBody(ids, store.pwm);
    for (let i = 0; i < 25 && !pulses && this.link === link; i++) {
      await new Promise((r) => setTimeout(r, 200));
      pulses = poseBody(ids, store.pwm);
    }
    const start = this.deps.startCopy ?? startModelCopy;
    const r: ModelCopyResult = await start(link.settings, pulses);
    if (this.link !== link || this.mode !== 'model') return;
    this.noteBad = !r.ok;
    this.note = r.ok
      ? `Commands go to the copy ${r.armId || 'of this arm'}${r.started ? ' (started)' : ''}; the arm stays still.`
      : `The model copy did not start (${r.error}): commands go to nothing real.`;
  }
}
