/**
 * Issue 9's part of the page, wired once in main.tsx: the fleet link, the active robot (profile
 * → store, 3D model, planner), and the Plan panel's plain objects (waypoints, the ghost's plan
 * preview, the runner that streams a plan). `switched` follows the Connection panel, the log-in
 * and the fleet list when the page moves to another arm or broker.
 */
import type { HudSettings } from '../config/settings.ts';
import type { ArmStore } from '../store/ArmStore.ts';
import type { Viewer } from '../scene/Viewer.ts';
import { PlanPreview } from '../panels/Plan/PlanPreview.ts';
import { PlanRunner } from '../panels/Plan/PlanRunner.ts';
import { WaypointEditor } from '../panels/Plan/WaypointEditor.ts';
import { Waypoints } from '../panels/Plan/Waypoints.ts';
import { ActiveRobot } from './ActiveRobot.ts';
import { FleetLink, type FleetConnect } from './FleetLink.ts';
import { RequestLog } from '../panels/Command/RequestLog.ts';

export class RobotsHub {
  fleet: FleetLink;
  readonly active: ActiveRobot;
  readonly waypoints = new Waypoints();
  readonly preview = new PlanPreview();
  readonly runner = new PlanRunner();
  /** Motion requests this page sent (Command box, Cartesian panel) and their feedback. */
  readonly requests = new RequestLog();
  editor: WaypointEditor | null = null;
  private unlisten: () => void;

  constructor(
    private readonly store: ArmStore,
    private readonly viewer: Viewer,
    private readonly connect: FleetConnect,
    settings: HudSettings,
    onChange: () => void,
  ) {
    this.fleet = new FleetLink(settings, connect);
    this.active = new ActiveRobot(store, viewer, this.fleet.profiles, onChange);
    this.unlisten = this.listen();
    viewer.ghostSource = this.preview;
    this.runner.onPlan((plan) =>
      this.preview.show(
        plan,
        this.store.opts.arm.servos.map((s) => s.polarity),
        performance.now(),
      ),
    );
  }

  private listen(): () => void {
    const a = this.fleet.onProfile((id, p) => this.active.announced(id, p));
    const b = this.fleet.onFeedback((f) => this.requests.take(f));
    return () => {
      a();
      b();
    };
  }

  start(armId: string): void {
    this.fleet.start();
    this.active.follow(armId);
  }

  /** After `viewer.start()` (the canvas is in the page): the waypoint spheres and dragging. */
  viewerStarted(): void {
    this.editor ??= new WaypointEditor(this.viewer, this.waypoints);
  }

  /** The page reconnected (another arm, broker or user): follow it. */
  switched(prev: HudSettings, next: HudSettings): void {
    this.runner.cancel(prev.armId === next.armId ? '' : 'stopped: another arm was selected');
    this.preview.clear();
    if (
      prev.brokerUrl !== next.brokerUrl ||
      prev.username !== next.username ||
      prev.password !== next.password
    ) {
      this.fleet.stop();
      this.unlisten();
      this.fleet = new FleetLink(next, this.connect);
      this.active.useProfiles(this.fleet.profiles);
      this.unlisten = this.listen();
      this.fleet.start();
    } else {
      this.fleet.select(next.armId);
    }
    this.active.follow(next.armId);
  }
}
