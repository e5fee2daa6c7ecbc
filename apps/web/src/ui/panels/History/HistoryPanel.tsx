/**
 * History: what the arm did, from the middleware's history API (InfluxDB). A collapsible panel
 * at the bottom of the view, between the columns (the emergency stop stays uncovered). Ranges
 * 5 min / 1 h / 24 h / custom; tabs for the charts, the tracking-error table and alarm log, the
 * replay, and the episodes (record, stop, discard, mark the loaded range; ./EpisodesView.tsx). Loads happen on user action (opening, a range, Refresh, a joint), never per frame.
 * API failures are shown as text in place of the view. Only the servos of the arm's current
 * profile are shown; others stored under the same arm id are named, not drawn (profileServos.ts).
 */
import { useCallback, useMemo, useRef, useState } from 'react';
import { useSettings, useArm, useReplay, useRobots } from '../../hud/HudParts.ts';
import { ChartsView } from './ChartsView.tsx';
import { HistoryApi } from './historyApi.ts';
import { authHeaders } from '../../../core/auth/whoami.ts';
import {
  loadAngles,
  loadOverview,
  servoId,
  type AngleViews,
  type OverviewViews,
} from './loadHistory.ts';
import { onlyProfileServos } from './profileServos.ts';
import { resolveRange, toLocalInput, type RangeChoice, type TimeRange } from './range.ts';
import { EpisodesApi } from './episodesApi.ts';
import { EpisodesView } from './EpisodesView.tsx';
import { ExportButton } from './ExportButton.tsx';
import { loadReplay, seekReplay } from './replayLoad.ts';
import { RangePicker } from './RangePicker.tsx';
import { ReplayControls } from './ReplayControls.tsx';
import { ReplayStrip } from './ReplayScrubber.tsx';
import { TablesView } from './TablesView.tsx';
import { clockTime, tableTime } from './format.ts';
import './history.css';

type Tab = 'charts' | 'tables' | 'replay' | 'episodes';
const TABS: { id: Tab; label: string }[] = [
  { id: 'charts', label: 'Charts' },
  { id: 'tables', label: 'Tracking, alarms & control' },
  { id: 'replay', label: 'Replay' },
  { id: 'episodes', label: 'Episodes' },
];
/** Tabs that show without a loaded range. */
const STANDALONE: readonly Tab[] = ['replay', 'episodes'];

function initialChoice(): RangeChoice {
  const now = Date.now();
  return {
    preset: '5m',
    customStart: toLocalInput(now - 3_600_000),
    customStop: toLocalInput(now),
  };
}

export function HistoryPanel() {
  const settings = useSettings();
  const store = useArm();
  const replay = useReplay();
  const robots = useRobots();
  const servos = store.opts.arm.servos;
  const sliders = robots.active.spec.sliders;
  // The replay's angles are the store's (§2 degrees of the store's profile; an angle servo's own
  // angle as stored): shown in joint units.
  const replayJoints = useMemo(
    () =>
      sliders.map((j) => ({
        name: j.name,
        unit: j.unit,
        value: (a: number) => j.valueFromAngle(a),
      })),
    [sliders],
  );
  const arm = settings.armId;
  const { apiBase, username, password } = settings;
  // Under `armtwin up` with users, /api wants the log-in's password (HTTP Basic).
  const api = useMemo(
    () => new HistoryApi({ base: apiBase, headers: authHeaders({ username, password }) }),
    [apiBase, username, password],
  );
  const episodesApi = useMemo(
    () => new EpisodesApi({ base: apiBase, headers: authHeaders({ username, password }) }),
    [apiBase, username, password],
  );
  const segmentSource = useMemo(
    () => ({ base: apiBase, headers: authHeaders({ username, password }) }),
    [apiBase, username, password],
  );
  // An imported dataset's episode runs on its own time, not the arm's history: not marked.
  const replayAt = useCallback(
    () => (replay.record && replay.record.dataset === undefined ? replay.clock.position : null),
    [replay],
  );
  const [choice, setChoice] = useState(initialChoice);
  const [tab, setTab] = useState<Tab>('charts');
  const [joint, setJoint] = useState(servoId(0));
  const [range, setRange] = useState<TimeRange | null>(null);
  const [overview, setOverview] = useState<OverviewViews | null>(null);
  /** Servos with data in the range that the arm's current profile does not have (not shown). */
  const [others, setOthers] = useState<string[]>([]);
  const [angles, setAngles] = useState<AngleViews | null>(null);
  const [rangeError, setRangeError] = useState<string | null>(null);
  const [loading, setLoading] = useState(false);
  const pending = useRef<AbortController | null>(null);

  const servoName = useCallback(
    (id: string) => servos.find((s) => s.id === Number(id))?.name ?? `servo ${id}`,
    [servos],
  );
  const servoIds = useMemo(() => servos.map((s) => servoId(s.id)), [servos]);

  const anglesSeq = useRef(0);
  /** Loads one joint's angles; only the latest request's answer is shown. */
  const fetchAngles = (r: TimeRange, id: string, signal?: AbortSignal) => {
    const seq = ++anglesSeq.current;
    setAngles(null);
    loadAngles(api, arm, r, id, signal)
      .then((v) => {
        if (seq === anglesSeq.current && !signal?.aborted) setAngles(v);
      })
      .catch((err: unknown) => setRangeError(String(err)));
  };

  const load = (next: RangeChoice = choice) => {
    const resolved = resolveRange(next, Date.now());
    if (!resolved.ok) return setRangeError(resolved.error);
    setRangeError(null);
    pending.current?.abort();
    const ac = (pending.current = new AbortController());
    setLoading(true);
    setRange(resolved.range);
    loadOverview(api, arm, resolved.range, ac.signal)
      .then((v) => {
        if (ac.signal.aborted) return;
        const mine = onlyProfileServos(v, servoIds);
        setOverview(mine.overview);
        setOthers(mine.others);
        setLoading(false);
      })
      .catch((err: unknown) => {
        setLoading(false);
        setRangeError(String(err));
      });
    fetchAngles(resolved.range, joint, ac.signal);
  };

  return (
    <details
      className="panel history"
      aria-labelledby="history-title"
      onToggle={(e) => {
        if (e.currentTarget.open && !range) load();
      }}
    >
      <summary>
        <h2 id="history-title">History</h2>
        <span className="dim" data-testid="history-range">
          {range
            ? `${arm}: ${tableTime(range.start, range.stop)} – ${clockTime(range.stop)}`
            : `${arm}: from storage`}
        </span>
      </summary>
      <RangePicker
        choice={choice}
        loading={loading}
        onLoad={() => load()}
        onChange={(next, now) => {
          setChoice(next);
          if (now) load(next);
        }}
      >
        <ExportButton api={api} arm={arm} profile={robots.active.spec.name} range={range} />
      </RangePicker>
      {rangeError && (
        <p className="history-error" role="alert">
          {rangeError}
        </p>
      )}
      <div className="tabs" role="tablist" aria-label="History views">
        {TABS.map((t) => (
          <button
            key={t.id}
            type="button"
            role="tab"
            id={`history-tab-${t.id}`}
            aria-selected={tab === t.id}
            aria-controls="history-tabpanel"
            className={tab === t.id ? 'on' : ''}
            onClick={() => setTab(t.id)}
          >
            {t.label}
          </button>
        ))}
      </div>
      <div
        className="history-body"
        role="tabpanel"
        id="history-tabpanel"
        aria-labelledby={`history-tab-${tab}`}
      >
        {overview && others.length > 0 && !STANDALONE.includes(tab) && (
          <p className="dim" data-testid="history-others">
            Not shown: {others.length === 1 ? 'servo' : 'servos'} {others.join(', ')}, recorded
            under {arm} but not in its current profile ({robots.active.spec.name}).
          </p>
        )}
        {!overview && !STANDALONE.includes(tab) && (
          <p className="dim">{loading ? 'Loading…' : 'Nothing loaded yet.'}</p>
        )}
        {overview && tab === 'charts' && (
          <ChartsView
            arm={arm}
            overview={overview}
            angles={angles}
            servoIds={servoIds}
            joint={joint}
            servoName={servoName}
            replayAt={replayAt}
            onJoint={(id) => {
              setJoint(id);
              if (range) fetchAngles(range, id);
            }}
          />
        )}
        {overview && tab === 'tables' && (
          <>
            <ReplayStrip player={replay} />
            <TablesView
              arm={arm}
              overview={overview}
              servoName={servoName}
              replayAt={replayAt}
              seek={(t) =>
                void seekReplay(api, arm, overview.range, replay, t).then(
                  (e) => e && setRangeError(e),
                )
              }
            />
          </>
        )}
        {tab === 'replay' && (
          <ReplayControls
            api={api}
            arm={arm}
            range={range}
            player={replay}
            joints={replayJoints}
            segments={segmentSource}
          />
        )}
        {tab === 'episodes' && (
          <EpisodesView
            api={episodesApi}
            arm={arm}
            profile={robots.active.spec.name}
            range={range}
            onReplay={(r) => {
              const next: RangeChoice = {
                preset: 'custom',
                customStart: toLocalInput(r.start, true),
                customStop: toLocalInput(r.stop, true),
              };
              setChoice(next);
              load(next);
              setTab('replay');
              void loadReplay(api, arm, r, replay).then((l) => !l.ok && setRangeError(l.error));
            }}
          />
        )}
      </div>
    </details>
  );
}
