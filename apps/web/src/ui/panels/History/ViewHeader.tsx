/** A view's heading with its "CSV" button (disabled while there is nothing to export). */
export function ViewHeader({
  title,
  csvLabel,
  onCsv,
}: {
  title: string;
  /** Accessible name of the button, e.g. "Download temperature CSV". */
  csvLabel: string;
  onCsv: (() => void) | null;
}) {
  return (
    <div className="history-view-head">
      <h3>{title}</h3>
      <button
        type="button"
        className="small"
        aria-label={csvLabel}
        disabled={!onCsv}
        onClick={() => onCsv?.()}
      >
        CSV
      </button>
    </div>
  );
}

/** The text shown in place of a view that failed to load. */
export function ViewError({ error }: { error: string }) {
  return (
    <p className="history-error" role="alert">
      {error}
    </p>
  );
}
