/**
 * "Download MCAP": the loaded range of the arm's history as an MCAP file for Foxglove or
 * Lichtblick, from the history API's `export` endpoint (the middleware's README, "Recordings
 * out"). With the arm's profile, so the file carries joint states and link transforms. The
 * request carries the log-in like every history request; a refusal is shown as text.
 */
import { useState } from 'react';
import { downloadBlob } from './download.ts';
import type { HistoryApi } from './historyApi.ts';
import type { TimeRange } from './range.ts';

export function ExportButton(props: {
  api: HistoryApi;
  arm: string;
  profile: string;
  range: TimeRange | null;
}) {
  const [busy, setBusy] = useState(false);
  const [error, setError] = useState<string | null>(null);
  const { api, arm, profile, range } = props;
  const download = async () => {
    if (!range) return;
    setBusy(true);
    setError(null);
    const got = await api.file('export', {
      arm,
      start: range.start,
      stop: range.stop,
      format: 'mcap',
      profile,
    });
    setBusy(false);
    if (got.ok) downloadBlob(got.data.name, got.data.blob);
    else setError(got.error);
  };
  return (
    <>
      <button
        type="button"
        disabled={!range || busy}
        title="The loaded range as an MCAP file for Foxglove or Lichtblick"
        onClick={() => void download()}
      >
        {busy ? 'Exporting…' : 'Download MCAP'}
      </button>
      {error && (
        <p className="history-error history-export-error" role="alert">
          {error}
        </p>
      )}
    </>
  );
}
