/**
 * Emergency stop: always visible, a button named "Emergency stop" and the Escape key, from
 * anywhere on the page. Publishes `#255PDST!` at QoS 1 and drops pending jogs.
 *
 * The stop never waits: it is published from native listeners (capture phase) in the
 * `pointerdown` / `keydown` handler itself — not on `click` (which comes only on release), not
 * through React's event system, no state update and no await before the publish — and
 * `ArmLink.emergencyStop` puts it on the socket before it returns. The 3D view may render in a
 * worker (scene/RenderHost.ts), so the page's main thread is idle when the press comes.
 */
import { useEffect, useRef, useState } from 'react';
import { useLink, useSession } from '../../hud/HudParts.ts';
import { useSampled } from '../../hud/useSampled.ts';
import './estop-roles.css';

export function EmergencyStopButton() {
  const link = useLink();
  const session = useSession();
  const [feedback, setFeedback] = useState('');
  const button = useRef<HTMLButtonElement>(null);
  // A role that may not publish (viewer) cannot stop the arm from this page: say so plainly.
  const perm = useSampled(() => session.permissions);
  const refused = perm !== null && !perm.stop;

  // Read live by the native handlers (the link is replaced on reconnect): no re-binding needed.
  const live = useRef({ link, refused });
  useEffect(() => {
    live.current = { link, refused };
  });

  useEffect(() => {
    const el = button.current;
    /** Publishes first; the feedback line (React state) only afterwards. */
    const stop = (): void => {
      if (live.current.refused) return;
      const sent = live.current.link.emergencyStop();
      setFeedback(
        sent
          ? `Stop sent ${new Date().toLocaleTimeString()}`
          : 'Not connected: stop NOT sent — cut the power',
      );
    };
    // A pointer press stops at once (on `pointerdown`); keyboard activation of the focused
    // button (Enter, Space) comes as a click with no press (`detail` 0), so only that is a stop.
    const onPointerDown = (): void => stop();
    const onClick = (e: MouseEvent): void => {
      if (e.detail === 0) stop();
    };
    const onKey = (e: KeyboardEvent): void => {
      if (e.key === 'Escape') stop();
    };
    el?.addEventListener('pointerdown', onPointerDown, { capture: true });
    el?.addEventListener('click', onClick, { capture: true });
    window.addEventListener('keydown', onKey, { capture: true });
    return () => {
      el?.removeEventListener('pointerdown', onPointerDown, { capture: true });
      el?.removeEventListener('click', onClick, { capture: true });
      window.removeEventListener('keydown', onKey, { capture: true });
    };
  }, []);

  return (
    <div className="estop">
      <button
        ref={button}
        type="button"
        className="estop-button"
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
