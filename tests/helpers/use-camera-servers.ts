/**
 * Camera servers (`@armtwin/camera`'s `serveCamera`) for a Vitest file: `start()` serves one
 * camera of arm1, `front`, from ffmpeg's test source (its frames carry the clock in the time
 * stripe) on a free port, with a short restart back-off, unless `options` say otherwise; every
 * server started is stopped in afterAll.
 */
import { afterAll } from 'vitest';
import { serveCamera, type ServedCameras } from '@armtwin/camera';

export type CameraServerOptions = Partial<Parameters<typeof serveCamera>[0]>;

export function useCameraServers(): (options?: CameraServerOptions) => Promise<ServedCameras> {
  const servers: ServedCameras[] = [];
  afterAll(async () => {
    await Promise.all(servers.map((s) => s.stop()));
  });
  return async (options = {}) => {
    const s = await serveCamera({
      cameras: [
        {
          armId: 'arm1',
          camId: 'front',
          label: 'Front',
          source: 'testsrc',
          pose: { position: [600, -400, 450], lookAt: [150, 0, 100] },
          fovDeg: 50,
        },
      ],
      port: 0,
      backoff: { minMs: 200, maxMs: 2000, factor: 2, healthyMs: 5000 },
      ...options,
    });
    servers.push(s);
    return s;
  };
}
