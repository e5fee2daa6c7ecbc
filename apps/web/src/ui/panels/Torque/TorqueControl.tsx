/**
 * Torque of a bus arm: off (every servo limp: move the arm by hand, positions keep streaming)
 * and on (the servos hold where they are), published on `arm/{id}/torque` (`0`/`1`, the bus
 * gateway's topic, docs/arm-side.md). An operator's right. The gateway does not report torque
 * back, so what is shown is what this page last sent, and when.
 */
import { useState } from 'react';
import { useLink } from '../../hud/HudParts.ts';
import { useSampled } from '../../hud/useSampled.ts';

export function TorqueControl({ onSent }: { onSent?(on: boolean): void }) {
  const link = useLink();
  const allowed = useSampled(() => link.mayMove);
  const [state, setState] = useState('Torque: on (as the gateway holds the arm)');
  const send = (on: boolean) => {
    if (!link.setTorque(on)) {
      setState('Torque: NOT sent (not connected, or this log-in may not move the arm)');
      return;
    }
    onSent?.(on);
    setState(
      `Torque ${on ? 'on: holding' : 'off: the arm is limp, move it by hand'} (sent ${new Date().toLocaleTimeString()})`,
    );
  };
  return (
    <div className="torque" role="group" aria-label="Torque">
      <div className="row">
        <button type="button" disabled={!allowed} onClick={() => send(false)}>
          Torque off
        </button>
        <button type="button" disabled={!allowed} onClick={() => send(true)}>
          Torque on
        </button>
      </div>
      <p className="dim" role="status" data-testid="torque-state">
        {state}
      </p>
    </div>
  );
}
