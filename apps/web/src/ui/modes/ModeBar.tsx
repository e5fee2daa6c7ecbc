/**
 * The mode switch, always on screen in the top bar beside the selected arm's name (also on the
 * phone layout): three buttons `Model`, `Shadow`, `Twin` (aria-pressed), and a line saying what
 * the mode means for the arm now (the copy starting, Shadow's reason). Outside every panel, so
 * Shadow mode (which turns the panels' controls off) never turns it off.
 */
import { useModes, useSettings } from '../hud/HudParts.ts';
import { useSampled } from '../hud/useSampled.ts';
import { ARM_MODES, modelArmId, SHADOW_REASON } from '../../core/link/modes.ts';

const NO_COPY = 'This arm cannot have a model copy (a copy itself, or an id over 26 characters)';
import './modes.css';

export function ModeBar() {
  const modes = useModes();
  const settings = useSettings();
  const snap = useSampled(() => ({
    mode: modes.mode,
    arm: settings.armId,
    note: modes.note,
    bad: modes.noteBad,
    copy: modelArmId(settings.armId) !== null,
  }));
  const note = snap.mode === 'shadow' ? SHADOW_REASON : snap.note;
  return (
    <div className={`mode-bar mode-${snap.mode ?? 'unknown'}`} data-testid="mode-bar">
      <span className="mode-arm" title="The selected arm">
        {snap.arm}
      </span>
      <div className="mode-switch" role="group" aria-label="Mode">
        {ARM_MODES.map((m) => (
          <button
            key={m.mode}
            type="button"
            className="mode-button"
            aria-pressed={snap.mode === m.mode}
            title={m.mode === 'model' && !snap.copy ? NO_COPY : m.title}
            disabled={snap.mode === null || (m.mode === 'model' && !snap.copy)}
            onClick={() => modes.set(m.mode)}
          >
            {m.label}
          </button>
        ))}
      </div>
      {note && (
        <span
          className={`mode-note${snap.bad ? ' bad' : ''}`}
          role="status"
          data-testid="mode-note"
        >
          {note}
        </span>
      )}
    </div>
  );
}
