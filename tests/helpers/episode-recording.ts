/**
 * The recording side of an episode test (tests/integration/export-lerobot.test.ts): a
 * middleware storing into InfluxDB and recording two test-source cameras of one arm (`front`,
 * H.264; `side`, MJPEG only; their frames carry the wall clock in the time stripe), and the wait
 * until an episode is whole in both: a report after its end stored, and a finished segment of
 * each camera reaching past it.
 */
import { serveCamera, type ServedCameras } from '@armtwin/camera';
import {
  select,
  waitForValue,
  type InfluxTarget,
  type MiddlewareProcess,
} from '../../apps/middleware/test/support/harness.ts';
import type { Middlewares } from './use-middlewares.ts';

/** The cameras recorded, by id. */
export const RECORDED_CAMS = ['front', 'side'] as const;

/**
 * Starts the middleware (flushing every 200 ms, 2 s camera segments in `cameraDir`) and the
 * camera server, and waits until a first frame is recorded.
 */
export async function startRecordedCameras(o: {
  mws: Middlewares;
  mqttUrl: string;
  arm: string;
  cameraDir: string;
}): Promise<{ mw: MiddlewareProcess; camera: ServedCameras }> {
  const mw = await o.mws.spawn({
    env: { FLUSH_INTERVAL_MS: '200', CAMERA_DIR: o.cameraDir, CAMERA_SEGMENT_S: '2' },
  });
  const camera = await serveCamera({
    cameras: [
      { armId: o.arm, camId: 'front', label: 'Front', source: 'testsrc', kinds: ['h264-ws'] },
      { armId: o.arm, camId: 'side', label: 'Side', source: 'testsrc', kinds: ['mjpeg'] },
    ],
    port: 0,
    mqttUrl: o.mqttUrl,
  });
  await camera.announced;
  await waitForValue(
    async () => ((await mw.metrics())['camera_frames_recorded_total'] ?? 0) > 0,
    true,
    30_000,
  );
  return { mw, camera };
}

/** Waits until the episode that ended at `stopMs` is stored and recorded whole. */
export async function waitEpisodeWhole(o: {
  influx: InfluxTarget;
  /** The arm's API: `http://…/api/arms/<arm>`. */
  api: string;
  arm: string;
  stopMs: number;
}): Promise<void> {
  // the whole episode stored: a report after its end is in influxd
  const q = `SELECT count("angle") FROM "servo" WHERE "arm" = '${o.arm}' AND time >= ${o.stopMs * 1000}u`;
  await waitForValue(
    async () => Number((await select(o.influx, q))[0]?.[1] ?? 0) > 0,
    true,
    20_000,
  );
  // the whole episode recorded: a finished segment reaches past its end
  const segments = async (cam: string) =>
    (
      (await (await fetch(`${o.api}/cameras/${cam}/segments`)).json()) as {
        segments: { endMs: number }[];
      }
    ).segments;
  for (const cam of RECORDED_CAMS)
    await waitForValue(
      async () => (await segments(cam)).some((s) => s.endMs >= o.stopMs),
      true,
      30_000,
    );
}
