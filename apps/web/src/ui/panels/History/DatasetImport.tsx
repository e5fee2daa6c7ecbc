/**
 * "Open a LeRobot dataset" in the replay's controls (docs/dataset.md, "Import"): pick the
 * dataset's folder (v3.0, or v2.1), choose an episode, and it plays on the amber sibling like
 * a stored range: its `observation.state` converted back to this robot's servo angles
 * (core/dataset), and each of its camera videos under it (./DatasetVideos.tsx). Nothing leaves
 * the page. "Make plan from this range" below then turns it into
 * a plan, to rehearse in Model mode and run through the controller's limits and zones.
 */
import { useState } from 'react';
import { useRobots } from '../../hud/HudParts.ts';
import type { ReplayPlayer } from '../../../core/replay/ReplayPlayer.ts';
import {
  readLerobotDataset,
  type DatasetFile,
  type LerobotDataset,
} from '../../../core/dataset/lerobotDataset.ts';
import { recordFromEpisode } from '../../../core/dataset/episodeRecord.ts';
import { fixed } from './format.ts';
import { DatasetVideos, type LoadedEpisode } from './DatasetVideos.tsx';

type Note = { text: string; bad: boolean };

/** The picked folder's files (`webkitRelativePath`: `<folder>/meta/info.json`). */
const datasetFiles = (list: FileList): DatasetFile[] =>
  Array.from(list, (f) => ({
    path: f.webkitRelativePath || f.name,
    arrayBuffer: () => f.arrayBuffer(),
    text: () => f.text(),
    blob: () => f,
  }));

export function DatasetImport(props: { player: ReplayPlayer }) {
  const robots = useRobots();
  const [dataset, setDataset] = useState<LerobotDataset | null>(null);
  const [episode, setEpisode] = useState(0);
  const [note, setNote] = useState<Note | null>(null);
  const [loaded, setLoaded] = useState<LoadedEpisode | null>(null);

  const open = (list: FileList | null) => {
    if (!list || list.length === 0) return;
    setNote({ text: 'Reading the dataset…', bad: false });
    readLerobotDataset(datasetFiles(list))
      .then((d) => {
        setDataset(d);
        setEpisode(d.episodes[0]?.index ?? 0);
        setNote({
          text: `${d.name || 'Dataset'}: LeRobot ${d.version}, ${d.episodes.length} episode(s) at ${d.fps} fps${d.robotType ? `, ${d.robotType}` : ''}.`,
          bad: false,
        });
      })
      .catch((err: unknown) => {
        setDataset(null);
        setNote({ text: `Not imported: ${(err as Error).message}`, bad: true });
      });
  };

  const play = () => {
    const ep = dataset?.episodes.find((e) => e.index === episode);
    if (!dataset || !ep) return;
    const spec = robots.active.spec;
    const r = recordFromEpisode(spec.profile.servos, dataset.names, ep, Date.now());
    if (!r.ok) return setNote({ text: `Not for ${spec.name}: ${r.error}.`, bad: true });
    props.player.load(r.record);
    setLoaded({ record: r.record, fps: dataset.fps, videos: ep.videos });
    const seconds = (r.record.stop - r.record.start) / 1000;
    setNote({
      text: `Episode ${ep.index} ("${ep.task}") loaded on the replay: ${ep.timestamps.length} frames, ${fixed(seconds, 1)} s. Play it, or make a plan from it.`,
      bad: false,
    });
  };

  return (
    <div className="history-import">
      <div className="replay-row">
        <label>
          Open a LeRobot dataset{' '}
          <input
            type="file"
            aria-label="LeRobot dataset folder"
            // The whole folder: meta/info.json, meta/tasks.*, data/…/*.parquet, videos/….
            {...{ webkitdirectory: '', directory: '' }}
            multiple
            onChange={(e) => open(e.currentTarget.files)}
          />
        </label>
        {dataset && (
          <>
            <select
              aria-label="Dataset episode"
              value={String(episode)}
              onChange={(e) => setEpisode(Number(e.currentTarget.value))}
            >
              {dataset.episodes.map((e) => (
                <option key={e.index} value={String(e.index)}>
                  {`${e.index}: ${e.task} (${e.timestamps.length} frames)`}
                </option>
              ))}
            </select>
            <button type="button" onClick={play}>
              Play episode
            </button>
          </>
        )}
      </div>
      {note && (
        <p className={`note ${note.bad ? 'bad' : 'ok'}`} role="status" data-testid="import-note">
          {note.text}
        </p>
      )}
      <DatasetVideos player={props.player} loaded={loaded} />
    </div>
  );
}
