/**
 * The cameras of the selected arm (PROTOCOL.md §7): the retained `arm/{armId}/camera/+`
 * announcements and their calibrations (`arm/{armId}/camera/+/calibration`, docs/protocol.md
 * § Cameras), read on the arm link's client (the link is rebuilt for each arm and log-in, so the
 * list follows the selected arm and the page's credentials). Plain state, no React: panels
 * sample `list`, `version` and `rejected`. Its decoders (./CameraDecoders.ts) play each camera
 * only while it is shown. Built and wired in src/ui/app/createHud.ts.
 */
import {
  ANNOUNCEMENT_REJECTIONS,
  calibrationFilter,
  calibrationTopic,
  cameraFilter,
  encodeCalibration,
  parseCalibration,
  parseCalibrationTopic,
  parseCameraMessage,
  type AnnouncementRejection,
  type CameraAnnouncement,
  type CameraCalibration,
  type CameraPose,
} from '@armtwin/camera/client';
import type { ArmLink } from '../link/ArmLink.ts';
import type { CameraCredentials } from './streamUrl.ts';
import { CameraDecoders } from './CameraDecoders.ts';

export interface ArmCamera extends CameraAnnouncement {
  camId: string;
  /** The retained calibration laid over the announced pose, when there is one. */
  calibration?: CameraCalibration;
}

/** Where a camera is and how wide it sees: its calibration, else its announcement. */
export interface CameraPlacement {
  pose: CameraPose;
  fovDeg: number;
}

/** Vertical field of view when neither the announcement nor a calibration gives one, degrees. */
export const DEFAULT_FOV_DEG = 50;

/** The pose and fov a camera is drawn with, or null when it has no pose at all. */
export function placementOf(c: ArmCamera): CameraPlacement | null {
  if (c.calibration) return { pose: c.calibration.pose, fovDeg: c.calibration.fovDeg };
  return c.pose ? { pose: c.pose, fovDeg: c.fovDeg ?? DEFAULT_FOV_DEG } : null;
}

/** What a camera's view draws into (kept by ./CameraDecoders.ts while the camera exists). */
export interface CameraPicture {
  canvas: HTMLCanvasElement;
  /** Frames drawn so far (a new one = the picture changed). */
  frames(): number;
}

/** The part of the arm link the hub uses. */
export type CameraLink = Pick<ArmLink, 'settings' | 'tap'> &
  Partial<Pick<ArmLink, 'publishRetained' | 'permissions'>>;

const emptyRejections = (): Record<AnnouncementRejection, number> =>
  Object.fromEntries(ANNOUNCEMENT_REJECTIONS.map((r) => [r, 0])) as Record<
    AnnouncementRejection,
    number
  >;

export class CameraHub {
  /** Bumped when a camera or its calibration appears, changes or goes. */
  version = 0;
  /** Rejected announcements and calibrations by reason (Status panel), since the page opened. */
  readonly rejected = emptyRejections();
  rejectedTotal = 0;
  /** The first message of the last rejection (Status panel's tooltip). */
  lastRejection = '';
  /** Bumped by every `attach` (another arm or log-in: the streams are opened again). */
  attachments = 0;
  /** The page's log-in, sent with each stream. */
  credentials: CameraCredentials = { username: '', password: '' };
  /** Plays each camera while it is shown, into the canvas its views display. */
  readonly decoders: CameraDecoders;
  private readonly cameras = new Map<string, CameraAnnouncement & { camId: string }>();
  /**
   * Calibrations by camId. Kept while the camera is gone (a camera server that restarts
   * removes and announces its camera again; the camera has not moved), but only shown with it.
   */
  private readonly calibrations = new Map<string, CameraCalibration>();
  private armId = '';
  private link: CameraLink | null = null;

  constructor() {
    this.decoders = new CameraDecoders(this);
  }

  /** The cameras, sorted by id, each with its calibration. */
  get list(): ArmCamera[] {
    return [...this.cameras.values()]
      .sort((a, b) => a.camId.localeCompare(b.camId))
      .map((c) => {
        const calibration = this.calibrations.get(c.camId);
        return calibration ? { ...c, calibration } : c;
      });
  }

  /** Follows the cameras of `link`'s arm; the previous arm's are forgotten. */
  attach(link: CameraLink): void {
    this.link = link;
    this.armId = link.settings.armId;
    this.credentials = {
      username: link.settings.username ?? '',
      password: link.settings.password ?? '',
    };
    this.attachments++;
    if (this.cameras.size > 0 || this.calibrations.size > 0) this.version++;
    this.cameras.clear();
    this.calibrations.clear();
    const armId = this.armId;
    const prefix = `arm/${armId}/camera/`;
    link.tap({
      filter: cameraFilter(armId),
      matches: (topic) => topic.startsWith(prefix) && topic.split('/').length === 4,
      onMessage: (topic, payload) => armId === this.armId && this.take(topic, payload),
    });
    link.tap({
      filter: calibrationFilter(armId),
      matches: (topic) => topic.startsWith(prefix) && topic.endsWith('/calibration'),
      onMessage: (topic, payload) => armId === this.armId && this.takeCalibration(topic, payload),
    });
  }

  /** Whether this page may write a calibration (an operator; the broker checks again). */
  get canCalibrate(): boolean {
    return Boolean(this.link?.publishRetained && this.link.permissions?.command);
  }

  /**
   * Publishes `placement` as `camId`'s calibration (retained), or clears it with null; every
   * page, this one included, takes it when the broker sends it back. False when not sent.
   */
  saveCalibration(camId: string, placement: CameraPlacement | null, by: string): boolean {
    const link = this.link;
    if (!link?.publishRetained || !this.canCalibrate) return false;
    const payload = placement
      ? encodeCalibration({ ...placement, by: by || 'anonymous', at: new Date().toISOString() })
      : '';
    return link.publishRetained(calibrationTopic(this.armId, camId), payload);
  }

  private reject(topic: string, reason: AnnouncementRejection, message: string): void {
    this.rejected[reason]++;
    this.rejectedTotal++;
    this.lastRejection = `${topic.slice(0, 120)}: ${message}`;
  }

  /** One message on `arm/{armId}/camera/{camId}`. */
  take(topic: string, payload: Uint8Array | string): void {
    const m = parseCameraMessage(topic, payload);
    switch (m.type) {
      case 'rejected':
        return this.reject(topic, m.reason, m.message);
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

  /** One message on `arm/{armId}/camera/{camId}/calibration`. */
  takeCalibration(topic: string, payload: Uint8Array | string): void {
    const ids = parseCalibrationTopic(topic);
    if (!ids) return this.reject(topic, 'bad-topic', 'not arm/{armId}/camera/{camId}/calibration');
    if (ids.armId !== this.armId) return;
    const m = parseCalibration(payload);
    switch (m.type) {
      case 'rejected':
        return this.reject(topic, m.reason, m.message);
      case 'removed':
        if (this.calibrations.delete(ids.camId)) this.version++;
        return;
      case 'calibration':
        this.calibrations.set(ids.camId, m.calibration);
        this.version++;
        return;
      default:
        return m satisfies never;
    }
  }
}
