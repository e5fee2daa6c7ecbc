/**
 * An imported LeRobot episode's cameras under the replay (docs/dataset.md, "Import"): each
 * `observation.images.<cam>` clip plays in step with the replayed joints, paused, scrubbed and
 * sped up with them, by the recorded-camera player (./ReplayVideo.tsx's CameraReplay) fed the
 * clip as one segment (core/dataset/episodeVideo.ts). The MP4 is the picked folder's own File,
 * shown through an object URL: nothing is uploaded or copied. Shown while the replay holds that
 * episode's record.
 */
import { useMemo } from 'react';
import { useSampled } from '../../hud/useSampled.ts';
import type { ReplayPlayer, ReplayRecord } from '../../../core/replay/ReplayPlayer.ts';
import type { DatasetFile, EpisodeVideo } from '../../../core/dataset/lerobotDataset.ts';
import { cameraName, clipSegment } from '../../../core/dataset/episodeVideo.ts';
import { CameraReplay } from './ReplayVideo.tsx';
import { ViewError } from './ViewHeader.tsx';

/** The episode on the replay: its record (episode time 0 at `record.start`) and cameras. */
export interface LoadedEpisode {
  record: ReplayRecord;
  fps: number;
  videos: EpisodeVideo[];
}

const blobOf = async (f: DatasetFile): Promise<Blob> =>
  f.blob ? f.blob() : new Blob([await f.arrayBuffer()], { type: 'video/mp4' });

function DatasetCamera(props: {
  player: ReplayPlayer;
  loaded: LoadedEpisode;
  video: EpisodeVideo;
}) {
  const { player, loaded, video } = props;
  const cam = cameraName(video.key);
  const { clip, file } = video;
  const segments = useMemo(
    () => (typeof clip === 'string' ? [] : [clipSegment(clip, loaded.record.start, loaded.fps)]),
    [clip, loaded],
  );
  const load = useMemo(() => () => blobOf(file!), [file]);
  if (typeof clip === 'string') return <ViewError error={`${cam}: ${clip}`} />;
  if (!file) return <ViewError error={`${cam}: ${clip.path} is not in the picked folder`} />;
  return (
    <CameraReplay
      player={player}
      camId={`dataset-${cam}`}
      label={`${cam} (dataset)`}
      segments={segments}
      load={load}
      codec={video.codec}
    />
  );
}

export function DatasetVideos(props: { player: ReplayPlayer; loaded: LoadedEpisode | null }) {
  const { player, loaded } = props;
  const current = useSampled(() => loaded !== null && player.record === loaded.record);
  if (!loaded || !current || loaded.videos.length === 0) return null;
  return (
    <div className="replay-videos">
      {loaded.videos.map((v) => (
        <DatasetCamera key={v.key} player={player} loaded={loaded} video={v} />
      ))}
    </div>
  );
}
