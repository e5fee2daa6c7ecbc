/**
 * Command box: "home", "open gripper", "move to 150 0 80", "line to …", "plan …" →
 * `parseCommand` (@armtwin/motion) against the arm's profile → a motion request on
 * `arm/{id}/request`; the arm's feedback (planned, executing, done, unreachable with its code in
 * words, failed with its message) is listed as it arrives, as text only. The tip line is the FK
 * of the pulses the arm reports. A command whose plan would take the hand (or a joint) below the
 * floor is refused here, before it is sent.
 */
import { useState } from 'react';
import { CODE_BELOW_FLOOR, parseCommand, planRequest, tipPose } from '@armtwin/motion';
import '../robots.css';
import { useRobots, useRequests, useLink, useArm } from '../../hud/HudParts.ts';
import { useSampled } from '../../hud/useSampled.ts';
import { feedbackWords } from '../../../core/robots/feedback.ts';
import { nextRequestId } from '../../../core/robots/RequestLog.ts';

export function CommandPanel() {
  const robots = useRobots();
  const log = useRequests();
  const link = useLink();
  const store = useArm();
  const [text, setText] = useState('');
  const [error, setError] = useState('');
  const fleet = robots.fleet;

  const snap = useSampled(() => {
    const motion = robots.active.motion;
    const pwm = Array.from(store.pwm);
    const tip =
      motion && pwm.length === motion.ids.length && pwm.every(Number.isFinite)
        ? tipPose(motion, pwm)
        : null;
    return {
      version: log.version,
      allowed: link.mayMove,
      connected: fleet.connected,
      tip: tip ? `x ${tip.x.toFixed(1)}, y ${tip.y.toFixed(1)}, z ${tip.z.toFixed(1)} mm` : '',
    };
  });

  const send = () => {
    const profile = robots.active.spec.profile;
    const id = nextRequestId();
    const r = parseCommand(text, id, profile);
    if (!r.ok) return setError(r.message);
    // The floor is checked here first (the arm checks it again): plan from where the arm is.
    const motion = robots.active.motion;
    const from = Array.from(store.pwm);
    if (motion && from.length === motion.ids.length && from.every(Number.isFinite)) {
      const out = planRequest(motion, r.request, from);
      if (out.status === 'unreachable' && out.code === CODE_BELOW_FLOOR)
        return setError(`Not sent: ${out.message.replace(/^targets\[\d+\]: /, '')}.`);
    }
    if (!fleet.request(r.request, link.control.requestTopic))
      return setError('Not sent: the broker is not connected.');
    store.commandedPwm.fill(NaN); // the arm now heads elsewhere than this page's last jog
    setError('');
    log.sent(id, text.trim());
  };

  return (
    <section className="panel command" aria-labelledby="command-title">
      <h2 id="command-title">Command</h2>
      <form
        className="command-form"
        onSubmit={(e) => {
          e.preventDefault();
          send();
        }}
      >
        <input
          type="text"
          aria-label="Command"
          placeholder="home · open gripper · move to 150 0 80"
          value={text}
          maxLength={120}
          onChange={(e) => {
            setText(e.currentTarget.value);
            setError('');
          }}
        />
        <button type="submit" disabled={!snap.allowed || !snap.connected || text.trim() === ''}>
          Send
        </button>
      </form>
      {error && (
        <p className="note bad" data-testid="command-error">
          {error}
        </p>
      )}
      <ol className="command-log" aria-live="polite" data-testid="command-log">
        {log.entries.map((e) => {
          const last = e.feedback[e.feedback.length - 1];
          return (
            <li key={e.id} data-testid="command-entry">
              <span className="command-text">{e.text}</span>{' '}
              <span
                className={`command-status ${last ? last.status : ''}`}
                data-testid="command-status"
                title={e.feedback.map((f) => feedbackWords(f)).join(' → ')}
              >
                {last ? feedbackWords(last) : 'sent…'}
              </span>
            </li>
          );
        })}
      </ol>
      <p className="dim small-print" data-testid="tip-pose">
        {snap.tip ? `Tip at ${snap.tip}` : 'Tip: no pose reported yet.'}
      </p>
    </section>
  );
}
