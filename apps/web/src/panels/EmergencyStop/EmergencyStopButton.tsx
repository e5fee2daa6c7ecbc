/**
 * Emergency stop: always visible, a button named "Emergency stop" and the Escape key, from
 * anywhere on the page. Publishes `#255PDST!` at QoS 1 and drops pending jogs.
 */
import { useCallback, useEffect, useState } from 'react';
import { useHud } from '../../hud/HudContext.ts';
import { useSampled } from '../../hud/useSampled.ts';
import './estop-roles.css';

export function EmergencyStopButton() {
  const { link, session } = useHud();
  const [feedback, setFeedback] = useState('');
  // A role that may not publish (viewer) cannot stop the arm from this page: say so plainly.
  const perm = useSampled(() => session.permissions);
  const refused = perm !== null && !perm.stop;

  const stop = useCallback(() => {
    if (refused) return;
    const sent = link.emergencyStop();
    setFeedback(
      sent
        ? `Stop sent ${new Date().toLocaleTimeString()}`
        : 'Not connected: stop NOT sent — cut the power',
    );
  }, [link, refused]);

  useEffect(() => {
    const onKey = (e: KeyboardEvent) => {
      if (e.key === 'Escape') stop();
    };
    window.addEventListener('keydown', onKey, { capture: true });
    return () => window.removeEventListener('keydown', onKey, { capture: true });
  }, [stop]);

  return (
    <div className="estop">
      <button
        type="button"
        className="estop-button"
        onClick={stop}
        disabled={refused}
        aria-keyshortcuts={refused ? undefined : 'Escape'}
        data-testid="estop"
      >
        {refused ? perm.stopRefusal : 'Emergency stop'}
      </button>
      <div className="estop-hint" role="status">
        {feedback ||
          (refused
            ? 'this account cannot publish'
            : perm?.stopUnconfirmed
              ? 'role unknown: the broker may refuse this stop — keep the physical stop at hand (Esc)'
              : 'or press Esc')}
      </div>
    </div>
  );
}
