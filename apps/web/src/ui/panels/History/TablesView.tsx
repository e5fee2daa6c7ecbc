/**
 * The tables tab: tracking error per joint (mean and maximum absolute error between commanded
 * and actual angle, samples compared — `/history/tracking`) and the alarm log (one row per
 * episode — `/history/alarms`) and the control log (who took, gave and lost control, refused
 * moves, the thermal model's early warnings — `/history/audit`). Every value is rendered as text.
 * All three are on the replay's time axis (./replayRow.ts): the row at the replay's instant is
 * marked — a joint's worst moment, an alarm's start, a control event — and a row's time, clicked,
 * moves the replay there. The replay's scrubber is repeated above them (./ReplayScrubber.tsx).
 */
import { alarmsCsv, auditCsv, csvFileName, trackingCsv } from './csv.ts';
import { downloadText } from './download.ts';
import { fixed } from './format.ts';
import type { OverviewViews } from './loadHistory.ts';
import type { AlarmEpisode, AlarmsAnswer, AuditAnswer, TrackingAnswer } from '@armtwin/api';
import type { ReplayAt } from './historyChart.ts';
import type { TableTimeline } from './replayRow.ts';
import { SeekTime } from './SeekTime.tsx';
import { TableSection } from './TableSection.tsx';

const KIND_WORDS: Record<string, string> = {
  'temp-warning': 'temperature ≥ 60 °C',
  'temp-critical': 'temperature ≥ 75 °C',
  undervoltage: 'supply < 6.5 V',
};

const peakText = (e: AlarmEpisode) =>
  e.kind === 'undervoltage' ? `${fixed(e.peak, 2)} V (lowest)` : `${fixed(e.peak, 1)} °C`;

/** Each row's time on the replay's axis. */
const worstAt = (d: TrackingAnswer) => d.joints.map((j) => j.maxAt);
const alarmStart = (d: AlarmsAnswer) => d.episodes.map((e) => e.start);
const eventAt = (d: AuditAnswer) => d.events.map((e) => e.at);
/** The marked row's attribute: the row at the replay's instant, for the eye and screen readers. */
const mark = (current: boolean) => (current ? { 'aria-current': 'time' as const } : {});

export function TablesView({
  arm,
  overview,
  servoName,
  replayAt,
  seek,
}: {
  arm: string;
  overview: OverviewViews;
  servoName: (id: string) => string;
  /** The replay's instant on the loaded range (null: no replay there). */
  replayAt: ReplayAt;
  /** Moves the replay to t (epoch ms), loading the range's replay first if needed. */
  seek: (t: number) => void;
}) {
  const { tracking, alarms, audit, range } = overview;
  // The replay's instant marks a row only inside the loaded range (else it is another range's).
  const onRange: ReplayAt = () => {
    const t = replayAt();
    return t !== null && t >= range.start && t <= range.stop ? t : null;
  };
  const timeline: TableTimeline = { replayAt: onRange, seek, ref: range.stop };
  const download = (kind: string, text: string) =>
    downloadText(csvFileName(arm, kind, range.start), text);
  return (
    <div className="history-tables">
      <TableSection
        title="Tracking error"
        csvLabel="Download tracking error CSV"
        view={tracking}
        csv={(d) => download('tracking', trackingCsv(d.joints, servoName))}
        items={(d) => d.joints}
        empty={<p className="dim">No commands or samples in this range.</p>}
        testId="tracking-table"
        columns={['Joint', 'Mean |err|', 'Max |err|', 'At', 'Samples']}
        times={worstAt}
        replayAt={onRange}
        row={(j, _, current) => (
          <tr key={j.id} data-testid={`tracking-${j.id}`} {...mark(current)}>
            <th scope="row">{servoName(j.id)}</th>
            <td>{j.meanAbsError === null ? '—' : `${fixed(j.meanAbsError)}°`}</td>
            <td>{j.maxAbsError === null ? '—' : `${fixed(j.maxAbsError)}°`}</td>
            <td>
              <SeekTime at={j.maxAt} timeline={timeline} />
            </td>
            <td>{j.samples}</td>
          </tr>
        )}
        notes={(d) =>
          d.thinnedEveryMs !== null && (
            <p className="dim small-print">
              One sample per {d.thinnedEveryMs / 1000} s compared; the true maximum may be missed.
            </p>
          )
        }
      />
      <TableSection
        title="Alarm log"
        csvLabel="Download alarm log CSV"
        view={alarms}
        csv={(d) => download('alarms', alarmsCsv(d.episodes, servoName))}
        items={(d) => d.episodes}
        empty={
          <p className="dim" data-testid="alarm-log">
            No alarms in this range.
          </p>
        }
        testId="alarm-log"
        columns={['Alarm', 'Servo', 'Start', 'End', 'Peak']}
        times={alarmStart}
        replayAt={onRange}
        row={(e, _, current) => (
          <tr key={`${e.kind}-${e.id}-${e.start}`} className={`alarm-${e.kind}`} {...mark(current)}>
            <td>{KIND_WORDS[e.kind] ?? e.kind}</td>
            <td>{servoName(e.id)}</td>
            <td>
              <SeekTime at={e.start} timeline={timeline} />
            </td>
            <td>{e.end === null ? 'ongoing' : <SeekTime at={e.end} timeline={timeline} />}</td>
            <td>{peakText(e)}</td>
          </tr>
        )}
        notes={(d) =>
          d.truncated && (
            <p className="warn small-print">
              Too many samples: the log covers only part of the range.
            </p>
          )
        }
      />
      <TableSection
        title="Control log"
        csvLabel="Download control log CSV"
        view={audit}
        csv={(d) => download('control-log', auditCsv(d.events))}
        items={(d) => d.events}
        empty={
          <p className="dim" data-testid="control-log">
            Nobody took, gave or lost control in this range.
          </p>
        }
        testId="control-log"
        columns={['When', 'Who', 'What']}
        times={eventAt}
        replayAt={onRange}
        row={(e, i, current) => (
          <tr key={`${e.at}-${i}`} className={`audit-${e.kind}`} {...mark(current)}>
            <td>
              <SeekTime at={e.at} timeline={timeline} />
            </td>
            <td>{e.by || 'plain control topic'}</td>
            <td>{e.detail || e.kind}</td>
          </tr>
        )}
        notes={(d) =>
          d.truncated && (
            <p className="warn small-print">Too many events: the log shows the first ones.</p>
          )
        }
      />
    </div>
  );
}
