/**
 * What the 3D view's translucent sibling arm shows (scene/ReplaySibling.ts): the History
 * panel's replay while one is loaded, else — in Model mode — the model copy, posed from the
 * copy's reported angles, beside the real arm (which keeps being drawn where it is). One source
 * for what the page sends the scene runtime (scene/render/FrameChanges.ts): no
 * change to the scene's frame loop. Allocation-free per frame.
 */
import type { SiblingSource } from '../store/viewSources.ts';
import type { ReplayPlayer } from '../replay/ReplayPlayer.ts';
import type { ArmStore } from '../store/ArmStore.ts';

export class SiblingFeed implements SiblingSource {
  private last = new Float64Array(0);
  private copyShown = false;

  /** `copy`: the copy's store while in Model mode, else null. */
  constructor(
    private readonly replay: ReplayPlayer,
    private readonly copy: () => ArmStore | null,
  ) {}

  private get replaying(): boolean {
    return this.replay.active && this.replay.record !== null;
  }

  get active(): boolean {
    return this.replaying || this.copyShown;
  }

  get record(): unknown {
    return this.replaying ? this.replay.record : this.copyShown ? this : null;
  }

  get angles(): Float64Array {
    return this.replaying ? this.replay.angles : (this.copy()?.angle ?? this.last);
  }

  update(now: number): boolean {
    const replayed = this.replay.update(now);
    if (this.replaying) {
      this.copyShown = false;
      return replayed;
    }
    const store = this.copy();
    const angle = store?.angle;
    const shown = angle !== undefined && angle.some(Number.isFinite);
    let changed = shown !== this.copyShown || replayed;
    this.copyShown = shown;
    if (!shown || !angle) return changed;
    if (this.last.length !== angle.length) this.last = new Float64Array(angle.length);
    for (let i = 0; i < angle.length; i++) {
      const a = angle[i]!;
      if (a !== this.last[i] && !(Number.isNaN(a) && Number.isNaN(this.last[i]!))) {
        this.last[i] = a;
        changed = true;
      }
    }
    return changed;
  }
}
