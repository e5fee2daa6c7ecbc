/**
 * The cameras of the selected arm (PROTOCOL.md §7): the retained `arm/{armId}/camera/+`
 * announcements, read on the arm link's client (the link is rebuilt for each arm and log-in, so
 * the list follows the selected arm and the page's credentials). Plain state, no React: panels
 * sample `list`, `version` and `rejected`. Built and wired in src/hud/createHud.ts.
 */
import {
  ANNOUNCEMENT_REJECTIONS,
  cameraFilter,
  parseCameraMessage,
  type AnnouncementRejection,
  type CameraAnnouncement,
} from '@armtwin/camera/announcement';
import type { ArmLink } from '../mqtt/ArmLink.ts';

export interface ArmCamera extends CameraAnnouncement {
  camId: string;
}

/** What a camera's view draws into (registered by the panel's view while it is mounted). */
export interface CameraPicture {
  canvas: HTMLCanvasElement;
  /** Frames drawn so far (a new one = the picture changed). */
  frames(): number;
}

const emptyRejections = (): Record<AnnouncementRejection, number> =>
  Object.fromEntries(ANNOUNCEMENT_REJECTIONS.map((r) => [r, 0])) as Record<
    AnnouncementRejection,
    number
  >;

export class CameraHub {
  /** Bumped when a camera appears, changes or goes. */
  version = 0;
  /** Rejected announcements by reason (Status panel), since the page opened. */
  readonly rejected = emptyRejections();
  rejectedTotal = 0;
  /** The first message of the last rejection (Status panel's tooltip). */
  lastRejection = '';
  /** The picture of each camera being played, by camId (the 3D view's screens use them). */
  readonly pictures = new Map<string, CameraPicture>();
  private readonly cameras = new Map<string, ArmCamera>();
  private armId = '';

  /** The cameras, sorted by id. */
  get list(): ArmCamera[] {
    return [...this.cameras.values()].sort((a, b) => a.camId.localeCompare(b.camId));
  }

  /** Follows the cameras of `link`'s arm; the previous arm's are forgotten. */
  attach(link: Pick<ArmLink, 'settings' | 'tap'>): void {
    this.armId = link.settings.armId;
    if (this.cameras.size > 0) this.version++;
    this.cameras.clear();
    const filter = cameraFilter(this.armId);
    const prefix = `arm/${this.armId}/camera/`;
    const armId = this.armId;
    link.tap({
      filter,
      matches: (topic) => topic.startsWith(prefix),
      onMessage: (topic, payload) => armId === this.armId && this.take(topic, payload),
    });
  }

  /** One message on `arm/{armId}/camera/{camId}`. */
  take(topic: string, payload: Uint8Array | string): void {
    const m = parseCameraMessage(topic, payload);
    switch (m.type) {
      case 'rejected':
        this.rejected[m.reason]++;
        this.rejectedTotal++;
        this.lastRejection = `${topic.slice(0, 120)}: ${m.message}`;
        return;
      case 'removed':
        if (this.cameras.delete(m.camId)) this.version++;
        return;
      case 'camera':
        if (m.armId !== this.armId) return;
        this.cameras.set(m.camId, { ...m.camera, camId: m.camId });
        this.version++;
        return;
      default:
        return m satisfies never;
    }
  }
}
