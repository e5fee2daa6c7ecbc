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
import { TableSection } from './TableSection.tsx';

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
        row={(j) => (
          <tr key={j.id} data-testid={`tracking-${j.id}`}>
            <th scope="row">{servoName(j.id)}</th>
            <td>{j.meanAbsError === null ? '—' : `${fixed(j.meanAbsError)}°`}</td>
            <td>{j.maxAbsError === null ? '—' : `${fixed(j.maxAbsError)}°`}</td>
            <td>{j.maxAt === null ? '—' : tableTime(j.maxAt, ref)}</td>
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
        row={(e) => (
          <tr key={`${e.kind}-${e.id}-${e.start}`} className={`alarm-${e.kind}`}>
            <td>{KIND_WORDS[e.kind] ?? e.kind}</td>
            <td>{servoName(e.id)}</td>
            <td>{tableTime(e.start, ref)}</td>
            <td>{e.end === null ? 'ongoing' : tableTime(e.end, ref)}</td>
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
        row={(e, i) => (
          <tr key={`${e.at}-${i}`} className={`audit-${e.kind}`}>
            <td>{tableTime(e.at, ref)}</td>
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
