/**
 * Which robot the HUD shows and controls: the selected arm's retained profile
 * (`arm/{id}/profile`, through the FleetLink), or armtwin5 when none has come within
 * `PROFILE_WAIT_MS` (an old arm, a real controller). A profile arriving later, or another arm
 * selected, switches again. Applying a robot: the store is sized for it, the view shows it (the
 * 3D model and the replay, posed through its joint map), and the planner's robot is built (a
 * numeric profile needs its URDF's chain). Plain object; `onChange` tells the page to re-render.
 */
import { chainFromUrdf, type Profile } from '@armtwin/robot';
import { createMotionRobot, type MotionRobot } from '@armtwin/motion';
import type { ArmStore } from '../store/ArmStore.ts';
import { DEFAULT_PROFILE, PROFILE_WAIT_MS } from './defaultProfile.ts';
import { robotSpec, type RobotSpec } from './robotSpec.ts';

/** Where a robot is shown: the 3D view and the replay (wired in src/ui/app/createHud.ts). */
export interface RobotView {
  /**
   * Shows `spec`'s robot, replacing the one shown: its URDF (`urdfUrl`, absolute), posed
   * through `spec.joints`. Resolves once its meshes have loaded.
   */
  show(spec: RobotSpec, urdfUrl: string): Promise<void>;
}

export type ProfileSource = 'announced' | 'assumed' | 'waiting';

export class ActiveRobot {
  spec: RobotSpec = robotSpec(DEFAULT_PROFILE);
  /** The planner's view of `spec` (null while a numeric robot's URDF loads, or if it failed). */
  motion: MotionRobot | null = null;
  source: ProfileSource = 'waiting';
  /** Bumped whenever `spec` changes (the page re-mounts the panels on it). */
  version = 0;
  /** The last model or profile that failed to load ('' = none). */
  error = '';
  /** Resolves once the first model has loaded (rejects if it failed). */
  readonly firstLoad: Promise<void>;
  private resolveFirst!: () => void;
  private rejectFirst!: (err: unknown) => void;
  private loaded = false;
  private loadedKey = '';
  private seq = 0;
  private timer: ReturnType<typeof setTimeout> | undefined;
  private armId = '';

  constructor(
    private readonly store: ArmStore,
    private readonly view: RobotView,
    private profiles: ReadonlyMap<string, Profile>,
    private readonly onChange: () => void,
    private readonly fetchText: (url: string) => Promise<string> = fetchUrdf,
  ) {
    this.firstLoad = new Promise((resolve, reject) => {
      this.resolveFirst = resolve;
      this.rejectFirst = reject;
    });
    this.firstLoad.catch(() => {}); // the page reports it
  }

  /** Shows `armId`'s robot: its announced profile, else armtwin5 after the wait. */
  follow(armId: string): void {
    this.armId = armId;
    clearTimeout(this.timer);
    const known = this.profiles.get(armId);
    if (known) return void this.apply(known, 'announced');
    this.source = 'waiting';
    this.timer = setTimeout(() => {
      if (this.armId === armId && !this.profiles.has(armId))
        void this.apply(DEFAULT_PROFILE, 'assumed');
    }, PROFILE_WAIT_MS);
  }

  /** A profile was announced (FleetLink.onProfile). */
  announced(armId: string, profile: Profile): void {
    if (armId !== this.armId) return;
    clearTimeout(this.timer);
    void this.apply(profile, 'announced');
  }

  /** Another fleet link (a new broker or user): its announced profiles. */
  useProfiles(profiles: ReadonlyMap<string, Profile>): void {
    this.profiles = profiles;
  }

  stop(): void {
    clearTimeout(this.timer);
  }

  private async apply(profile: Profile, source: ProfileSource): Promise<void> {
    const key = JSON.stringify(profile);
    this.source = source;
    if (key === this.loadedKey) return this.onChange();
    const seq = ++this.seq;
    const spec = robotSpec(profile);
    if (JSON.stringify(this.store.opts.arm) !== JSON.stringify(spec.storeArm))
      this.store.configure(spec.storeArm);
    this.spec = spec;
    this.motion = null;
    this.version++;
    this.onChange();
    try {
      await this.view.show(spec, new URL(spec.urdfUrl, document.baseURI).href);
      const motion =
        profile.ik.kind === 'analytic5'
          ? createMotionRobot(profile)
          : await this.numericRobot(profile, spec.urdfUrl);
      if (seq !== this.seq) return;
      this.motion = motion;
      this.loadedKey = key;
      this.error = '';
      if (!this.loaded) {
        this.loaded = true;
        this.resolveFirst();
      }
    } catch (err) {
      if (seq !== this.seq) return;
      this.error = err instanceof Error ? err.message : String(err);
      if (!this.loaded) this.rejectFirst(err);
    }
    this.onChange();
  }

  private async numericRobot(profile: Profile, urdfUrl: string): Promise<MotionRobot> {
    const text = await this.fetchText(new URL(urdfUrl, document.baseURI).href);
    const chain = chainFromUrdf(profile, text);
    if (!chain.ok) throw new Error(`${profile.name}: ${chain.errors.join('; ')}`);
    return createMotionRobot(profile, chain.chain);
  }
}

async function fetchUrdf(url: string): Promise<string> {
  const res = await fetch(url);
  if (!res.ok) throw new Error(`could not load ${url}: HTTP ${res.status}`);
  return res.text();
}
