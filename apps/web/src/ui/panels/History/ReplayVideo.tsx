/**
 * The replay's cameras: every camera of the arm plays its recorded video (the middleware's MP4
 * segments, docs/cameras-recording.md) on the replay's time axis, beside the amber arm. For the
 * replay's instant t, each camera's <video> shows the segment covering t at media time
 * t − segment start (core/replay/videoAt.ts; the next segment is fetched while one plays,
 * core/replay/segmentsAhead.ts), kept in step with the replay clock on every
 * animation frame: played and paused with it, at its speed, moved when it is scrubbed; a gap in
 * the recording shows "no recording"; a video the browser cannot decode (its codec) says so in
 * its place (`undecodableWords`). An MJPEG camera's `.mjpeg` segments are shown frame by
 * frame in an <img> instead (./ReplayJpegs.ts). The cameras are those the arm announces (the
 * camera hub).
 */
import { useEffect, useMemo, useRef, useState } from 'react';
import { useCameras } from '../../hud/HudParts.ts';
import { useSampled } from '../../hud/useSampled.ts';
import type { ReplayPlayer } from '../../../core/replay/ReplayPlayer.ts';
import { needsSeek, videoAt, type RecordedSegment } from '../../../core/replay/videoAt.ts';
import { isJpegSegment } from '../../../core/replay/jpegFrames.ts';
import { SegmentsAhead } from '../../../core/replay/segmentsAhead.ts';
import { JpegReplay } from './ReplayJpegs.ts';
import { fetchSegment, listSegments } from './cameraSegmentsApi.ts';
import type { Loaded } from './loaded.ts';
import { ViewError } from './ViewHeader.tsx';

export interface SegmentSource {
  base: string;
  headers?: Record<string, string>;
}

/** One camera's <video>, driven by the replay clock (also an imported dataset's: ./DatasetVideos.tsx). */
export function CameraReplay(props: {
  player: ReplayPlayer;
  camId: string;
  label: string;
  segments: readonly RecordedSegment[];
  /** One segment's MP4 (fetched whole, the next one ahead: core/replay/segmentsAhead.ts). */
  load: (name: string) => Promise<Blob>;
  /** The video's codec where it is known (a dataset's info.json), named if it cannot be decoded. */
  codec?: string | null;
}) {
  const { player, segments, load } = props;
  const video = useRef<HTMLVideoElement>(null);
  const img = useRef<HTMLImageElement>(null);
  const [gap, setGap] = useState(true);
  const [jpeg, setJpeg] = useState(false);
  const [failed, setFailed] = useState<string | null>(null);
  const [undecodable, setUndecodable] = useState<string | null>(null);
  useEffect(() => {
    let raf = 0;
    let shownGap: boolean | null = null;
    let shownJpeg = false;
    // the segment played and the next one, fetched while this one plays: no pause at the boundary
    const ahead = new SegmentsAhead(load);
    const get = (name: string) => ahead.get(segments, name);
    const jpegs = new JpegReplay(get, setFailed);
    /** The segment asked for, and the blob: URL of the one in the <video>. */
    let wanted = '';
    let objectUrl = '';
    const show = (name: string, startMs: number) => {
      wanted = name;
      get(name).then(
        (blob) => {
          if (wanted !== name || !video.current) return;
          if (objectUrl) URL.revokeObjectURL(objectUrl);
          objectUrl = URL.createObjectURL(blob);
          video.current.dataset.segmentStart = String(startMs);
          video.current.src = objectUrl;
          setFailed(null);
          setUndecodable(null);
        },
        (err: unknown) => wanted === name && setFailed(String(err)),
      );
    };
    const step = () => {
      raf = requestAnimationFrame(step);
      const v = video.current;
      if (!v) return;
      const clock = player.clock;
      const at = player.record ? videoAt(segments, clock.position) : null;
      if ((at === null) !== shownGap) setGap((shownGap = at === null));
      if (!at) {
        if (!v.paused) v.pause();
        return;
      }
      const isJpeg = isJpegSegment(at.segment.name);
      if (isJpeg !== shownJpeg) setJpeg((shownJpeg = isJpeg));
      if (isJpeg) {
        if (!v.paused) v.pause();
        if (img.current) jpegs.step(img.current, at.segment, clock.position);
        return;
      }
      if (wanted !== at.segment.name) show(at.segment.name, at.segment.startMs);
      if (v.dataset.segmentStart !== String(at.segment.startMs)) return; // still loading
      if (v.readyState < HTMLMediaElement.HAVE_METADATA) return;
      if (v.playbackRate !== clock.speed) v.playbackRate = clock.speed;
      if (!v.seeking && needsSeek(v.currentTime, at.offsetS, clock.playing))
        v.currentTime = at.offsetS;
      if (clock.playing && v.paused) v.play().catch(() => undefined);
      else if (!clock.playing && !v.paused) v.pause();
    };
    raf = requestAnimationFrame(step);
    return () => {
      cancelAnimationFrame(raf);
      jpegs.dispose();
      wanted = '';
      if (objectUrl) URL.revokeObjectURL(objectUrl);
    };
  }, [player, segments, load]);

  return (
    <figure className="replay-video" data-testid={`replay-video-${props.camId}`}>
      <video
        ref={(v) => {
          video.current = v;
          if (v) v.muted = true;
        }}
        aria-label={`Recorded video of ${props.label}`}
        playsInline
        preload="auto"
        hidden={gap || jpeg || undecodable !== null}
        onError={(e) => {
          const words = undecodableWords(props.label, props.codec ?? null, e.currentTarget.error);
          if (words) setUndecodable(words);
        }}
      />
      <img ref={img} alt={`Recorded pictures of ${props.label}`} hidden={gap || !jpeg} />
      {gap && <p className="replay-video-gap dim">{props.label}: no recording</p>}
      {failed && <ViewError error={failed} />}
      {undecodable && !gap && !jpeg && <ViewError error={undecodable} />}
      <figcaption className="dim small-print">{props.label}</figcaption>
    </figure>
  );
}

/**
 * What stands in place of a video the browser cannot decode (its codec, or a file it cannot
 * read as video); null for other media errors (a load aborted by the next segment).
 */
export function undecodableWords(
  label: string,
  codec: string | null,
  error: MediaError | null,
): string | null {
  if (!error) return null;
  if (
    error.code !== MediaError.MEDIA_ERR_SRC_NOT_SUPPORTED &&
    error.code !== MediaError.MEDIA_ERR_DECODE
  )
    return null;
  const what = codec ? `its ${codec} video` : 'its video';
  const detail = error.message ? ` (${error.message})` : '';
  return `${label}: this browser cannot decode ${what}, so no picture is shown; the joints replay without it${detail}.`;
}

export function ReplayVideos(props: { player: ReplayPlayer; arm: string; source: SegmentSource }) {
  const { player, arm, source } = props;
  const { hub } = useCameras();
  const s = useSampled(() => ({
    ids: hub.list.map((c) => c.camId),
    labels: hub.list.map((c) => c.label || c.camId),
    start: player.record ? player.clock.start : NaN,
    stop: player.record ? player.clock.stop : NaN,
  }));
  const idsKey = s.ids.join('\n');
  /** The lists answered for this record and these cameras (older answers are not shown). */
  const loadKey = `${arm} ${s.start} ${s.stop} ${idsKey}`;
  const [lists, setLists] = useState<{
    key: string;
    byCam: Record<string, Loaded<RecordedSegment[]>>;
  }>({ key: '', byCam: {} });
  useEffect(() => {
    if (Number.isNaN(s.start)) return;
    let gone = false;
    for (const cam of idsKey ? idsKey.split('\n') : []) {
      void listSegments(source, arm, cam, { start: s.start, stop: s.stop }).then((l) => {
        if (gone) return;
        setLists((prev) => ({
          key: loadKey,
          byCam: { ...(prev.key === loadKey ? prev.byCam : {}), [cam]: l },
        }));
      });
    }
    return () => {
      gone = true;
    };
  }, [s.start, s.stop, idsKey, arm, source, loadKey]);
  const byCam = lists.key === loadKey ? lists.byCam : {};
  const loaders = useMemo(
    () =>
      Object.fromEntries(
        s.ids.map((cam) => [cam, (name: string) => fetchSegment(source, arm, cam, name)]),
      ),
    // eslint-disable-next-line react-hooks/exhaustive-deps -- idsKey stands for s.ids
    [idsKey, source, arm],
  );

  if (Number.isNaN(s.start)) return null;
  if (s.ids.length === 0)
    return <p className="dim small-print">No camera announced for {arm}: joints only.</p>;
  return (
    <div className="replay-videos">
      {s.ids.map((cam, i) => {
        const l = byCam[cam];
        if (!l) return <p key={cam} className="dim">{`${s.labels[i]}: loading…`}</p>;
        if (!l.ok) return <ViewError key={cam} error={l.error} />;
        return (
          <CameraReplay
            key={cam}
            player={player}
            camId={cam}
            label={s.labels[i]!}
            segments={l.data}
            load={loaders[cam]!}
          />
        );
      })}
    </div>
  );
}
