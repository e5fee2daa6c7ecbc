/**
 * Who controls the selected arm, under the arm list (docs/protocol.md § Control): `Take
 * control` when nobody does; "Controlled by <name>" and `Ask for control` when someone else
 * does (the move controls elsewhere are then off, the emergency stop never is); the holder
 * sees each request with `Grant` / `Refuse`, and `Release control`. The arm enforces it; this
 * only mirrors the controller's retained `arm/{id}/holder` and its events about this user.
 */
import { useLink, useSettings } from '../../hud/HudParts.ts';
import { useSampled } from '../../hud/useSampled.ts';

export function ControlBar() {
  const link = useLink();
  const { armId } = useSettings();
  const snap = useSampled(() => {
    const c = link.control;
    return {
      known: c.holder !== null,
      me: c.who.name,
      enforced: c.who.enforced,
      admin: c.who.admin,
      holding: c.holding,
      heldBy: c.heldBy,
      asked: c.asked,
      requests: c.holding ? (c.holder?.requests ?? []) : [],
      mayCommand: link.permissions.command,
      notice: c.notice?.detail ?? '',
      noticeKind: c.notice?.kind ?? '',
    };
  });
  const c = () => link.control;
  const who = snap.enforced ? snap.me : `${snap.me} (self-declared)`;
  const warn = snap.noticeKind.startsWith('refused') || snap.noticeKind === 'lost';
  return (
    <div className="control-bar" data-testid="control-bar">
      <p className="control-holder" role="status" data-testid="control-holder">
        {!snap.known
          ? 'Control: the arm has not said who holds it.'
          : snap.holding
            ? `You control ${armId} as ${who}.`
            : snap.heldBy
              ? `Controlled by ${snap.heldBy}`
              : `Nobody controls ${armId}.`}
      </p>
      {snap.mayCommand && snap.known && (
        <div className="control-actions">
          {!snap.holding && (!snap.heldBy || snap.admin) && (
            <button type="button" onClick={() => c().take()}>
              Take control
            </button>
          )}
          {!!snap.heldBy && !snap.asked && (
            <button type="button" onClick={() => c().ask()}>
              Ask for control
            </button>
          )}
          {snap.asked && <span className="dim">Asked {snap.heldBy}; waiting…</span>}
          {snap.holding && (
            <button type="button" onClick={() => c().release()}>
              Release control
            </button>
          )}
        </div>
      )}
      {snap.requests.length > 0 && (
        <ul className="control-requests" aria-label="Requests for control">
          {snap.requests.map((user) => (
            <li key={user}>
              <span>{user} asks for control</span>
              <button type="button" onClick={() => c().grant(user)}>
                Grant
              </button>
              <button type="button" onClick={() => c().refuse(user)}>
                Refuse
              </button>
            </li>
          ))}
        </ul>
      )}
      {snap.notice && (
        <p className={`note${warn ? ' warn' : ''}`} data-testid="control-notice">
          {snap.notice}
        </p>
      )}
    </div>
  );
}
