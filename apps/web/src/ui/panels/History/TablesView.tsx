/**
 * The tables tab: tracking error per joint (mean and maximum absolute error between commanded
 * and actual angle, samples compared — `/history/tracking`) and the alarm log (one row per
 * episode — `/history/alarms`) and the control log (who took, gave and lost control, refused
 * moves, the thermal model's early warnings — `/history/audit`). Every value is rendered as text.
 */
import { alarmsCsv, auditCsv, csvFileName, trackingCsv } from './csv.ts';
import { downloadText } from './download.ts';
import { fixed, tableTime } from './format.ts';
import type { OverviewViews } from './loadHistory.ts';
import type { AlarmEpisode } from '@armtwin/api';
import { ViewError, ViewHeader } from './ViewHeader.tsx';

const KIND_WORDS: Record<string, string> = {
  'temp-warning': 'temperature ≥ 60 °C',
  'temp-critical': 'temperature ≥ 75 °C',
  undervoltage: 'supply < 6.5 V',
};

const peakText = (e: AlarmEpisode) =>
  e.kind === 'undervoltage' ? `${fixed(e.peak, 2)} V (lowest)` : `${fixed(e.peak, 1)} °C`;

export function TablesView({
  arm,
  overview,
  servoName,
}: {
  arm: string;
  overview: OverviewViews;
  servoName: (id: string) => string;
}) {
  const { tracking, alarms, audit, range } = overview;
  const ref = range.stop;
  return (
    <div className="history-tables">
      <section className="history-view" aria-label="Tracking error">
        <ViewHeader
          title="Tracking error"
          csvLabel="Download tracking error CSV"
          onCsv={
            tracking.ok
              ? () =>
                  downloadText(
                    csvFileName(arm, 'tracking', range.start),
                    trackingCsv(tracking.data.joints, servoName),
                  )
              : null
          }
        />
        {!tracking.ok && <ViewError error={tracking.error} />}
        {tracking.ok && tracking.data.joints.length === 0 && (
          <p className="dim">No commands or samples in this range.</p>
        )}
        {tracking.ok && tracking.data.joints.length > 0 && (
          <table className="history-table" data-testid="tracking-table">
            <thead>
              <tr>
                <th scope="col">Joint</th>
                <th scope="col">Mean |err|</th>
                <th scope="col">Max |err|</th>
                <th scope="col">At</th>
                <th scope="col">Samples</th>
              </tr>
            </thead>
            <tbody>
              {tracking.data.joints.map((j) => (
                <tr key={j.id} data-testid={`tracking-${j.id}`}>
                  <th scope="row">{servoName(j.id)}</th>
                  <td>{j.meanAbsError === null ? '—' : `${fixed(j.meanAbsError)}°`}</td>
                  <td>{j.maxAbsError === null ? '—' : `${fixed(j.maxAbsError)}°`}</td>
                  <td>{j.maxAt === null ? '—' : tableTime(j.maxAt, ref)}</td>
                  <td>{j.samples}</td>
                </tr>
              ))}
            </tbody>
          </table>
        )}
        {tracking.ok && tracking.data.thinnedEveryMs !== null && (
          <p className="dim small-print">
            One sample per {tracking.data.thinnedEveryMs / 1000} s compared; the true maximum may be
            missed.
          </p>
        )}
      </section>
      <section className="history-view" aria-label="Alarm log">
        <ViewHeader
          title="Alarm log"
          csvLabel="Download alarm log CSV"
          onCsv={
            alarms.ok
              ? () =>
                  downloadText(
                    csvFileName(arm, 'alarms', range.start),
                    alarmsCsv(alarms.data.episodes, servoName),
                  )
              : null
          }
        />
        {!alarms.ok && <ViewError error={alarms.error} />}
        {alarms.ok && alarms.data.episodes.length === 0 && (
          <p className="dim" data-testid="alarm-log">
            No alarms in this range.
          </p>
        )}
        {alarms.ok && alarms.data.episodes.length > 0 && (
          <table className="history-table" data-testid="alarm-log">
            <thead>
              <tr>
                <th scope="col">Alarm</th>
                <th scope="col">Servo</th>
                <th scope="col">Start</th>
                <th scope="col">End</th>
                <th scope="col">Peak</th>
              </tr>
            </thead>
            <tbody>
              {alarms.data.episodes.map((e) => (
                <tr key={`${e.kind}-${e.id}-${e.start}`} className={`alarm-${e.kind}`}>
                  <td>{KIND_WORDS[e.kind] ?? e.kind}</td>
                  <td>{servoName(e.id)}</td>
                  <td>{tableTime(e.start, ref)}</td>
                  <td>{e.end === null ? 'ongoing' : tableTime(e.end, ref)}</td>
                  <td>{peakText(e)}</td>
                </tr>
              ))}
            </tbody>
          </table>
        )}
        {alarms.ok && alarms.data.truncated && (
          <p className="warn small-print">
            Too many samples: the log covers only part of the range.
          </p>
        )}
      </section>
      <section className="history-view" aria-label="Control log">
        <ViewHeader
          title="Control log"
          csvLabel="Download control log CSV"
          onCsv={
            audit.ok
              ? () =>
                  downloadText(
                    csvFileName(arm, 'control-log', range.start),
                    auditCsv(audit.data.events),
                  )
              : null
          }
        />
        {!audit.ok && <ViewError error={audit.error} />}
        {audit.ok && audit.data.events.length === 0 && (
          <p className="dim" data-testid="control-log">
            Nobody took, gave or lost control in this range.
          </p>
        )}
        {audit.ok && audit.data.events.length > 0 && (
          <table className="history-table" data-testid="control-log">
            <thead>
              <tr>
                <th scope="col">When</th>
                <th scope="col">Who</th>
                <th scope="col">What</th>
              </tr>
            </thead>
            <tbody>
              {audit.data.events.map((e, i) => (
                <tr key={`${e.at}-${i}`} className={`audit-${e.kind}`}>
                  <td>{tableTime(e.at, ref)}</td>
                  <td>{e.by || 'plain control topic'}</td>
                  <td>{e.detail || e.kind}</td>
                </tr>
              ))}
            </tbody>
          </table>
        )}
        {audit.ok && audit.data.truncated && (
          <p className="warn small-print">Too many events: the log shows the first ones.</p>
        )}
      </section>
    </div>
  );
}
