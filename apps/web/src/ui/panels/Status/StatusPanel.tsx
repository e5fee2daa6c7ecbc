/**
 * Status: broker connection, arm online/offline (retained `arm/{id}/online`), message rate,
 * live `$PNG` round trip, what each reader dropped (the arm's status stream; the fleet's
 * reports of the other arms, with its rejected profiles and feedback), history storage, and a
 * stale-data warning when no state report has come for more than 1 s, and whether the arm is
 * drawn ahead of its reports (the predictive twin: "Predicted", with the lead in ms).
 */
import {
  useArm,
  useSettings,
  useLink,
  useRobots,
  useCameras,
  useRendering,
  useSceneFigures,
} from '../../hud/HudParts.ts';
import { useSampled } from '../../hud/useSampled.ts';
import { useStorageStatus } from './useStorageStatus.ts';
import {
  CONNECTION_WORDS,
  armWords,
  cameraRejects,
  fleetRejects,
  formatRate,
  renderWords,
  twinWords,
} from './words.ts';
import { gapWords } from '../../../core/link/GapTracker.ts';
import { droppedWords } from '../../../core/store/readerErrors.ts';
import { SOFTWARE_PACING } from '../../../scene/FramePacer.ts';
import { drawnLeadMs } from '../../../scene/render/SceneReports.ts';

export function StatusPanel() {
  const store = useArm();
  const settings = useSettings();
  const link = useLink();
  const robots = useRobots();
  const { hub: cameras } = useCameras();
  const rendering = useRendering();
  const view = useSceneFigures();
  const storage = useStorageStatus();
  const s = useSampled(() => {
    const now = performance.now();
    const rtt = store.ping.rttMs;
    const pingFresh = now - store.ping.lastEchoAt < 3000;
    return {
      connection: store.connection,
      error: store.connectionError,
      brokerInUse: link.brokerInUse,
      online: store.armOnline,
      onlineText: store.armOnlineText,
      gap: gapWords(link.gap.view(Date.now())),
      stale: store.isStale(now),
      staleFor: Number.isNaN(store.lastStateAt)
        ? NaN
        : Math.round((now - store.lastStateAt) / 100) / 10,
      messages: formatRate(store.messageRatePerS(now)),
      states: formatRate(store.stateRatePerS(now)),
      rtt: pingFresh && !Number.isNaN(rtt) ? `${rtt.toFixed(rtt < 10 ? 1 : 0)} ms` : '—',
      dropped: store.counters.dropped,
      droppedKinds: droppedWords(store.counters.droppedByKind),
      fleetRejected: fleetRejects(robots.fleet.counters),
      fleetFirstErrors: Object.values(robots.fleet.firstError).join('\n'),
      cameras: cameras.list.length,
      cameraRejected: cameraRejects(cameras.rejectedTotal, cameras.rejected),
      cameraLastRejection: cameras.lastRejection,
      published: store.counters.published,
      controllerError: store.lastControllerError,
      twinMode: store.opts.twinMode,
      predicting: store.predicting,
      leadMs: Math.round(drawnLeadMs(store, view.reports)),
      rendering: renderWords({
        ...rendering,
        software: view.software,
        frameCostMs: view.frameCostMs,
        budget: SOFTWARE_PACING.budget,
      }),
    };
  });

  return (
    <section className="panel status" aria-labelledby="status-title">
      <h2 id="status-title">
        Status <span className="dim">· arm/{settings.armId}</span>
      </h2>
      <dl className="kv">
        <dt>Broker</dt>
        <dd data-testid="broker-state" className={s.connection === 'connected' ? 'ok' : 'bad'}>
          {CONNECTION_WORDS[s.connection]}
          {s.error && s.connection !== 'connected' ? ` (${s.error})` : ''}
          {s.brokerInUse && s.connection === 'connected' && (
            <span className="dim" data-testid="broker-in-use">
              {' '}
              · {s.brokerInUse}
            </span>
          )}
        </dd>
        <dt>Arm</dt>
        <dd
          data-testid="arm-online"
          className={s.online === true ? 'ok' : s.online === false ? 'bad' : ''}
        >
          {armWords(s.online)}
          {s.onlineText && <span className="dim"> (unrecognised: “{s.onlineText}”)</span>}
        </dd>
        <dt>Messages</dt>
        <dd>
          {s.messages}/s <span className="dim">(state {s.states}/s)</span>
        </dd>
        <dt>Ping</dt>
        <dd data-testid="ping-rtt">{s.rtt}</dd>
        <dt>Dropped</dt>
        <dd data-testid="dropped" title={s.droppedKinds}>
          {s.dropped} frame{s.dropped === 1 ? '' : 's'}
          {s.droppedKinds && <span className="dim"> ({s.droppedKinds})</span>}
        </dd>
        <dt>Fleet</dt>
        <dd data-testid="fleet-rejects" title={s.fleetFirstErrors}>
          {s.fleetRejected || 'nothing refused'}
        </dd>
        <dt>Cameras</dt>
        <dd data-testid="camera-rejects" title={s.cameraLastRejection}>
          {s.cameras} announced
          {s.cameraRejected && <span className="dim"> · {s.cameraRejected}</span>}
        </dd>
        <dt>Sent</dt>
        <dd>{s.published} commands</dd>
        <dt>History</dt>
        <dd data-testid="storage" className={storage === 'on' ? 'ok' : 'warn'}>
          {storage === 'on'
            ? 'history storage on'
            : storage === 'off'
              ? 'history storage off'
              : 'checking…'}
        </dd>
      </dl>
      {s.gap && (
        <p
          className={`note ${s.connection === 'connected' ? 'warn' : 'bad'}`}
          data-testid="broker-gap"
        >
          {s.gap}
        </p>
      )}
      {s.controllerError && <p className="note warn">Controller error: {s.controllerError}</p>}
      <p className={`note ${s.stale ? 'stale' : 'fresh'}`} role="status" data-testid="freshness">
        {s.stale
          ? Number.isNaN(s.staleFor)
            ? 'No data from the arm yet: data is stale.'
            : `Data is stale: no status for ${s.staleFor.toFixed(1)} s. Jogging is disabled.`
          : 'Data is live.'}
      </p>
      <p
        className={`note twin ${s.predicting ? 'predicted' : 'dim'}`}
        data-testid="twin-prediction"
        data-predicting={s.predicting ? 'true' : 'false'}
      >
        {twinWords(s.twinMode, s.predicting, s.leadMs)}
      </p>
      <p className="note dim" data-testid="render-thread" data-thread={rendering.thread}>
        {s.rendering}
      </p>
    </section>
  );
}
