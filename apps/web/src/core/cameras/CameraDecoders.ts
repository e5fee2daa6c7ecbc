/**
 * Plays each camera of the hub only while it is shown somewhere: the Cameras panel unfolded, its
 * screen inside the 3D view's frustum, or the 3D view looking through it. A camera that is not
 * shown has no stream open and decodes nothing; shown again, it connects again (the last
 * picture stays in its canvas meanwhile). Each camera has one canvas for its whole life, which
 * the panel's view displays and the 3D view uses as a texture; frames never touch React.
 */
import { type CameraStream } from '@armtwin/camera/client';
import type { CameraHub, CameraPicture } from './CameraHub.ts';
import type { CameraPlayer, CameraPlayerStats } from './CameraPlayer.ts';
import { H264Player, hasVideoDecoder } from './H264Player.ts';
import { MjpegPlayer } from './MjpegPlayer.ts';
import { pickStream, usableUrl, type CameraCredentials } from './streamUrl.ts';

/** Makes the player of one stream (a test may hand in another). */
export type PlayerFactory = (
  canvas: HTMLCanvasElement,
  stream: CameraStream,
  url: URL,
  credentials: CameraCredentials,
) => CameraPlayer;

export const defaultPlayer: PlayerFactory = (canvas, stream, url, credentials) =>
  stream.kind === 'h264-ws'
    ? new H264Player(canvas, url, credentials)
    : new MjpegPlayer(canvas, url, credentials);

interface Entry {
  canvas: HTMLCanvasElement;
  picture: CameraPicture;
  player: CameraPlayer | null;
  /** What the player plays (kind, URL, log-in generation): another = a new player. */
  key: string;
  /** Frames drawn by this camera's earlier players. */
  before: number;
}

export class CameraDecoders {
  /** The picture of each camera, by camId (the 3D view's screens and view-through use them). */
  readonly pictures = new Map<string, CameraPicture>();
  private readonly entries = new Map<string, Entry>();
  private panelOpen = true;
  private readonly inScene = new Set<string>();
  private viewing = '';
  private seenVersion = -1;
  private seenAttachments = -1;

  constructor(
    private readonly hub: Pick<CameraHub, 'list' | 'version' | 'credentials' | 'attachments'>,
    private readonly makePlayer: PlayerFactory = defaultPlayer,
    private readonly canDecodeH264: () => boolean = hasVideoDecoder,
    private readonly makeCanvas: () => HTMLCanvasElement = () => document.createElement('canvas'),
  ) {}

  /** The Cameras panel folded (false) or unfolded (true). */
  setPanelOpen(open: boolean): void {
    if (open === this.panelOpen) return;
    this.panelOpen = open;
    this.sync();
  }

  /** What the 3D view shows: the cameras whose screens are in view, and the one looked through. */
  setScene(inScene: ReadonlySet<string>, viewing: string): void {
    let same = viewing === this.viewing && inScene.size === this.inScene.size;
    if (same) for (const id of inScene) same &&= this.inScene.has(id);
    if (same) return;
    this.viewing = viewing;
    this.inScene.clear();
    for (const id of inScene) this.inScene.add(id);
    this.sync();
  }

  /** Follows the hub (a camera came, changed or went; another log-in). Cheap: call it often. */
  update(): void {
    if (this.hub.version === this.seenVersion && this.hub.attachments === this.seenAttachments)
      return;
    this.sync();
  }

  /** The canvas `camId`'s views display (made on first use, kept while the camera exists). */
  canvasOf(camId: string): HTMLCanvasElement {
    return this.entry(camId).canvas;
  }

  /** The playing stream's counters, or null while the camera is not shown. */
  stats(camId: string): CameraPlayerStats | null {
    return this.entries.get(camId)?.player?.stats ?? null;
  }

  /** Whether `camId`'s stream is open now. */
  playing(camId: string): boolean {
    return Boolean(this.entries.get(camId)?.player);
  }

  private entry(camId: string): Entry {
    let e = this.entries.get(camId);
    if (!e) {
      const canvas = this.makeCanvas();
      canvas.width = 640;
      canvas.height = 480;
      canvas.className = 'camera-canvas';
      const made: Entry = {
        canvas,
        picture: { canvas, frames: () => made.before + (made.player?.stats.frames ?? 0) },
        player: null,
        key: '',
        before: 0,
      };
      e = made;
      this.entries.set(camId, e);
      this.pictures.set(camId, e.picture);
    }
    return e;
  }

  private stop(e: Entry): void {
    if (!e.player) return;
    e.before += e.player.stats.frames;
    e.player.dispose();
    e.player = null;
    e.key = '';
  }

  private sync(): void {
    this.seenVersion = this.hub.version;
    this.seenAttachments = this.hub.attachments;
    const cams = this.hub.list;
    const ids = new Set(cams.map((c) => c.camId));
    for (const [id, e] of this.entries)
      if (!ids.has(id)) {
        this.stop(e);
        this.entries.delete(id);
        this.pictures.delete(id);
      }
    for (const cam of cams) {
      const e = this.entry(cam.camId);
      const stream = pickStream(cam, this.canDecodeH264());
      const url = stream ? usableUrl(stream) : null;
      const shown = this.panelOpen || this.viewing === cam.camId || this.inScene.has(cam.camId);
      if (!shown || !stream || !url) {
        this.stop(e);
        continue;
      }
      const key = `${stream.kind} ${stream.url} ${this.hub.attachments}`;
      if (e.player && e.key === key) continue;
      this.stop(e);
      e.player = this.makePlayer(e.canvas, stream, url, this.hub.credentials);
      e.key = key;
      e.player.start();
    }
  }
}
