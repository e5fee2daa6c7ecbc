/**
 * `armtwin up --camera <source>`: one camera of the first arm, served on the up's own HTTP port
 * (`/camera/demo.mjpeg`, the `/camera/demo.h264` WebSocket) and announced on its broker through an
 * in-process client with the arm's device role. Without ffmpeg the twin starts without it and
 * says why: `npm start` needs nothing else.
 */
import type http from 'node:http';
import {
  createCameraServer,
  ffmpegVersion,
  startAnnouncer,
  type Announcer,
  type CameraPose,
  type CameraServer,
} from '@armtwin/camera';
import type { Broker, UpgradeHandler } from '@armtwin/broker';

export interface CameraPartOptions {
  /** `testsrc`, a V4L2 device, an `rtsp://` URL or an `http(s)://` MJPEG URL. */
  source: string;
  armId: string;
  broker: Broker;
  /** The API token that may watch too ('' = none). */
  apiToken: string;
  /** This run's token of the in-process middleware, which records the camera. */
  recorderToken: string;
  say: (msg: string) => void;
  onFirst: (kind: string, message: string) => void;
}

/** Where the demo camera stands: 600 mm out in front, 400 mm up, looking at the arm. */
export const DEMO_CAMERA = {
  camId: 'demo',
  label: 'Demo camera',
  pose: { position: [600, 0, 400], lookAt: [0, 0, 150] } satisfies CameraPose,
  fovDeg: 50,
};

export interface CameraPart {
  handleRequest(req: http.IncomingMessage, res: http.ServerResponse): boolean;
  handleUpgrade: UpgradeHandler;
  /** Announces the camera at `baseUrl` (`http(s)://host:port`, what the page reaches). */
  announce(baseUrl: string): void;
  stop(): Promise<void>;
}

/** The camera, or null (and a line saying why) when ffmpeg is missing. */
export function createCameraPart(o: CameraPartOptions): CameraPart | null {
  const version = ffmpegVersion();
  if (version === null) {
    o.say('camera: ffmpeg is not installed (apt install ffmpeg); starting without the camera');
    return null;
  }
  const server: CameraServer = createCameraServer({
    cameras: [{ armId: o.armId, source: o.source, ...DEMO_CAMERA }],
    access: { logins: o.broker.logins, token: o.apiToken, recorderToken: o.recorderToken },
    onFirst: o.onFirst,
  });
  server.start();
  let announcer: Announcer | null = null;
  return {
    handleRequest: (req, res) => server.handleRequest(req, res),
    handleUpgrade: (req, socket, head) => server.handleUpgrade(req, socket, head),
    announce(baseUrl) {
      const [a] = server.announcements(baseUrl);
      if (!a) return;
      announcer = startAnnouncer({
        mqttUrl: o.broker.url,
        topic: a.topic,
        announcement: a.announcement,
        onFirst: o.onFirst,
        connect: (_url, opts) =>
          o.broker.connectInProcess(
            { name: `camera-${o.armId}`, role: 'device', arm: o.armId },
            opts,
          ),
      });
      o.say(`camera: ${a.announcement.url} (${o.source}; ${version})`);
    },
    async stop() {
      await announcer?.stop();
      await server.stop();
    },
  };
}
