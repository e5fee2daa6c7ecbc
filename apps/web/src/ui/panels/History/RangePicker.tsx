/**
 * The time range: 5 min, 1 h, 24 h (ending now) or custom (two local date-times), and Refresh;
 * `children` (the export) end the same row.
 */
import type { ReactNode } from 'react';
import { RANGE_PRESETS, type RangeChoice, type RangePreset } from './range.ts';

export function RangePicker({
  choice,
  onChange,
  onLoad,
  loading,
  children,
}: {
  children?: ReactNode;
  choice: RangeChoice;
  onChange: (next: RangeChoice, loadNow: boolean) => void;
  onLoad: () => void;
  loading: boolean;
}) {
  const presets: { id: RangePreset; label: string }[] = [
    ...RANGE_PRESETS,
    { id: 'custom', label: 'Custom' },
  ];
  return (
    <div className="history-range">
      <div className="segmented" role="radiogroup" aria-label="Time range">
        {presets.map((p) => (
          <label key={p.id} className={choice.preset === p.id ? 'on' : ''}>
            <input
              type="radio"
              name="history-range"
              value={p.id}
              checked={choice.preset === p.id}
              onChange={() => onChange({ ...choice, preset: p.id }, p.id !== 'custom')}
            />
            {p.label}
          </label>
        ))}
      </div>
      {choice.preset === 'custom' && (
        <div className="history-custom">
          <label>
            From{' '}
            <input
              type="datetime-local"
              value={choice.customStart}
              onChange={(e) => onChange({ ...choice, customStart: e.currentTarget.value }, false)}
            />
          </label>
          <label>
            to{' '}
            <input
              type="datetime-local"
              value={choice.customStop}
              onChange={(e) => onChange({ ...choice, customStop: e.currentTarget.value }, false)}
            />
          </label>
        </div>
      )}
      <button type="button" onClick={onLoad} disabled={loading}>
        {loading ? 'Loading…' : choice.preset === 'custom' ? 'Show' : 'Refresh'}
      </button>
      {children}
    </div>
  );
}
