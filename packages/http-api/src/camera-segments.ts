/**
 * `/arms/{id}/cameras/{cam}/segments`: a camera's recorded segments (docs/cameras-recording.md).
 * `GET …/segments?from=&to=` (ISO times, both optional) lists those holding any frame of the
 * range, by time: `{ok, segments: [{name, start, end, bytes, url}]}`; `GET …/segments/{name}`
 * sends one (`video/mp4`, or the multipart JPEGs of an `.mjpeg` one; immutable: a finished
 * segment never changes), or the one byte range asked for (206), so a `<video>` can seek. Anyone who may read the
 * history may read them; without the middleware's recording the route answers 503.
 */
import type http from 'node:http';
import { MJPEG_CONTENT_TYPE } from '@armtwin/camera';
import { isValidCamId } from '@armtwin/camera/announcement';
import { isValidArmId } from '@armtwin/protocol';
import {
  callerMay,
  countedAnswer,
  methodIn,
  type May,
  type RouteCounters,
} from './counted-answer.ts';
import { sendFile } from './send-file.ts';
import type { ApiService } from './service-routes.ts';
import { TIME_RANGE_ERROR, timeRange } from './time-range.ts';

/** A finished segment: its file name and the epoch ms of its first frame and its end. */
export interface CameraSegment {
  name: string;
  startMs: number;
  endMs: number;
  bytes: number;
}

/** What the middleware lends the route. */
export interface CameraSegmentService {
  segments(armId: string, camId: string, fromMs?: number, toMs?: number): CameraSegment[];
  /** The path of a finished segment, or null when there is none of that name. */
  file(armId: string, camId: string, name: string): string | null;
}

export function cameraSegmentsRoute(o: {
  service: () => ApiService | null;
  mayRead: May;
  onFirst(kind: string, message: string): void;
}) {
  const counters: RouteCounters = {};
  const answer = countedAnswer('camera-segments', counters, o.onFirst);
  return {
    counters,
    async handle(
      req: http.IncomingMessage,
      res: http.ServerResponse,
      p: { id: string; cam: string; name?: string },
    ) {
      if (!methodIn(req, res, ['GET', 'HEAD'])) return;
      if (!(await callerMay(o.mayRead, req, res, answer))) return;
      if (!isValidArmId(p.id) || !isValidCamId(p.cam))
        return answer(res, 400, { ok: false, errors: ['not an arm or camera id'] }, 'refused:id');
      const cameras = o.service()?.cameras;
      if (!cameras)
        return answer(
          res,
          503,
          { ok: false, errors: ['no camera recording here: CAMERA_RECORD is off'] },
          'failed:recording',
        );
      if (p.name !== undefined) {
        const file = cameras.file(p.id, p.cam, p.name);
        if (!file) return answer(res, 404, { ok: false, errors: ['no such segment'] }, 'missing');
        counters.sent = (counters.sent ?? 0) + 1;
        const type = file.endsWith('.mjpeg') ? MJPEG_CONTENT_TYPE : 'video/mp4';
        return sendFile(req, res, file, type, 'public, max-age=31536000, immutable', {
          ranges: true,
        });
      }
      const range = timeRange(req);
      if (!range)
        return answer(res, 400, { ok: false, errors: [TIME_RANGE_ERROR] }, 'refused:request');
      const base = (req.url ?? '').split('?')[0]!.replace(/\/$/, '');
      const segments = cameras.segments(p.id, p.cam, range.from, range.to).map((s) => ({
        name: s.name,
        start: new Date(s.startMs).toISOString(),
        end: new Date(s.endMs).toISOString(),
        startMs: s.startMs,
        endMs: s.endMs,
        bytes: s.bytes,
        url: `${base}/${s.name}`,
      }));
      return answer(res, 200, { ok: true, segments }, 'listed');
    },
  };
}
