/**
 * The camera-recording bench's recorder (../dataset.ts): the middleware's own `Recordings`
 * (apps/middleware/src/cameras) recording one `h264-ws` URL into a folder, alone in its process
 * so its CPU (node + its ffmpeg segmenter) can be read from /proc. Prints `{"ready":true}`, and
 * on SIGTERM finishes its segments and prints its counters.
 * Usage: recorder.ts <h264-ws url> <dir> <segment s>
 */
import { encodeAnnouncement } from '@armtwin/camera/announcement';
import { Recordings } from '../../apps/middleware/src/cameras/index.ts';

const [url = '', dir = '', segmentS = '10'] = process.argv.slice(2);
const recordings = new Recordings({
  dir,
  segmentS: Number(segmentS),
  maxAgeMs: 0,
  maxBytes: 0,
  onFirst: (kind, message) => process.stderr.write(`recorder: ${kind}: ${message}\n`),
});
recordings.handle(
  'arm/bench-rec/camera/front',
  encodeAnnouncement({ url, kind: 'h264-ws', label: 'bench', alternates: [] }),
);
process.stdout.write(`${JSON.stringify({ ready: true })}\n`);
process.once('SIGTERM', () => {
  void recordings.stop().then(() => {
    const c = recordings.counters;
    process.stdout.write(
      `${JSON.stringify({ frames: c.frames, bytes: c.bytesIn, events: c.events })}\n`,
    );
    process.exit(0);
  });
});
