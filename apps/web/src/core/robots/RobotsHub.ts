/**
 * The robots the page knows: the fleet link (every arm on the broker; the selected arm's motion
 * requests and feedback) and the active robot (the selected arm's profile → store, view,
 * planner). `switched` follows the Connection panel, the log-in and the fleet list when the page
 * moves to another arm or broker: a new broker or user gets a new fleet link, and the feedback
 * listeners carry over to it. Built and wired in src/ui/app/createHud.ts.
 */
import type { HudSettings } from '../config/settings.ts';
import type { ArmStore } from '../store/ArmStore.ts';
import { ActiveRobot, type RobotView } from './ActiveRobot.ts';
import type { Feedback } from './feedback.ts';
import { FleetLink, type FleetConnect } from './FleetLink.ts';

export class RobotsHub {
  fleet: FleetLink;
  readonly active: ActiveRobot;
  private readonly feedbackListeners = new Set<(f: Feedback) => void>();
  private unlisten: () => void;

  constructor(
    store: ArmStore,
    view: RobotView,
    private readonly connect: FleetConnect,
    settings: HudSettings,
    onChange: () => void,
  ) {
    this.fleet = new FleetLink(settings, connect);
    this.active = new ActiveRobot(store, view, this.fleet.profiles, onChange);
    this.unlisten = this.listen();
  }

  /** The selected arm's motion feedback, from whichever fleet link is current. */
  onFeedback(fn: (f: Feedback) => void): () => void {
    this.feedbackListeners.add(fn);
    return () => this.feedbackListeners.delete(fn);
  }

  private listen(): () => void {
    const a = this.fleet.onProfile((id, p) => this.active.announced(id, p));
    const b = this.fleet.onFeedback((f) => {
      for (const fn of this.feedbackListeners) fn(f);
    });
    return () => {
      a();
      b();
    };
  }

  start(armId: string): void {
    this.fleet.start();
    this.active.follow(armId);
  }

  /** The page reconnected (another arm, broker or user): follow it. */
  switched(prev: HudSettings, next: HudSettings): void {
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
