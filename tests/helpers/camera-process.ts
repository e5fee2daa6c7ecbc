/**
 * A camera server in a process of its own, for tests that kill it (a crash): runs `serveCamera`
 * with the JSON options of argv[2], and prints one JSON line `{url, ffmpegPid}` once every
 * camera is announced. Run as `node --import tsx tests/helpers/camera-process.ts '<json>'`.
 */
import { serveCamera, type ServeCameraOptions } from '@armtwin/camera';

const options = JSON.parse(process.argv[2] ?? '{}') as Partial<ServeCameraOptions> &
  Pick<ServeCameraOptions, 'cameras'>;
const served = await serveCamera(options);
await served.announced;
const camId = options.cameras[0]?.camId ?? '';
process.stdout.write(
  `${JSON.stringify({ url: served.url, ffmpegPid: served.server.ffmpegPid(camId) })}\n`,
);
const stop = () => void served.stop().then(() => process.exit(0));
process.on('SIGTERM', stop);
process.on('SIGINT', stop);
