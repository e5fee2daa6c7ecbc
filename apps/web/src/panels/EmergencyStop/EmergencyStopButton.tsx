/**
 * Emergency stop: always visible, a button named "Emergency stop" and the Escape key, from
 * anywhere on the page. Publishes `#255PDST!` at QoS 1 and drops pending jogs.
 */
import { useCallback, useEffect, useState } from 'react';
import { useHud } from '../../hud/HudContext.ts';

export function EmergencyStopButton() {
  const { link } = useHud();
  const [feedback, setFeedback] = useState('');

  const stop = useCallback(() => {
    const sent = link.emergencyStop();
    setFeedback(
      sent
        ? `Stop sent ${new Date().toLocaleTimeString()}`
        : 'Not connected: stop NOT sent — cut the power',
    );
  }, [link]);

  useEffect(() => {
    const onKey = (e: KeyboardEvent) => {
      if (e.key === 'Escape') stop();
    };
    window.addEventListener('keydown', onKey, { capture: true });
    return () => window.removeEventListener('keydown', onKey, { capture: true });
  }, [stop]);

  return (
    <div className="estop">
      <button type="button" className="estop-button" onClick={stop} aria-keyshortcuts="Escape">
        Emergency stop
      </button>
      <div className="estop-hint" role="status">
        {feedback || 'or press Esc'}
      </div>
    </div>
  );
}
