/**
 * Cartesian target: X, Y, Z (mm) and an optional Pitch (degrees; blank = the controller picks,
 * as §4's search does). Every edit runs the local IK (@armtwin/ik): the ghost shows the
 * solution, or the status code is shown in words, before anything is sent. "Move" publishes
 * `$KMS:…!` only for a target the local IK accepts, and shows the arm's reply code. On an arm
 * whose profile is not `analytic5` (track6) the IK is the numeric one and "Move" sends a motion
 * request (`arm/{id}/request`, joint mode) instead (solveTarget.ts).
 * A click on the floor in the 3D view places the target there (X, Y; Z kept). The fields start
 * at the active arm's tip (FK of where it is, else of its home pose): a point it can reach.
 */
import { useEffect, useMemo, useState } from 'react';
import { useArm, useLink, useTarget, useRobots, useRequests } from '../../hud/HudParts.ts';
import { useSampled } from '../../hud/useSampled.ts';
import { parseTarget, type TargetFields } from '../../../core/cartesian/parseTarget.ts';
import { codeWords, solveTarget, startFields } from '../../../core/cartesian/solveTarget.ts';
import { nextRequestId } from '../../../core/robots/RequestLog.ts';

/** The target's inputs and their visible labels (also their accessible names). */
const CART_FIELDS = [
  ['x', 'X'],
  ['y', 'Y'],
  ['z', 'Z'],
  ['pitch', 'Pitch'],
] as const;

export function CartesianPanel() {
  const store = useArm();
  const link = useLink();
  const target = useTarget();
  const robots = useRobots();
  const requests = useRequests();
  const motion = robots.active.motion;
  // Until edited, the fields hold where this arm's tip is (its planner may load after mount).
  const start = useMemo(() => startFields(motion, store.pwm), [motion, store]);
  const [edited, setEdited] = useState<TargetFields | null>(null);
  const fields = edited ?? start;
  const touched = edited !== null;
  const [sent, setSent] = useState<{ text: string; replies: number } | null>(null);
  const [refusal, setRefusal] = useState('');

  const parsed = parseTarget(fields);
  const result = parsed.ok
    ? solveTarget(
        parsed.x,
        parsed.y,
        parsed.z,
        parsed.pitch,
        store.opts.arm,
        robots.active.motion,
        store.pwm,
      )
    : null;
  const ikCodeMessage = (code: number) =>
    code === result?.code && (result.floor ?? result.zone)
      ? (result.floor ?? result.zone!.message)
      : codeWords(code, result?.via ?? 'kms');

  // Mirror the preview into the plain store the 3D view reads (marker and ghost).
  useEffect(() => {
    if (!touched || !parsed.ok || !result) {
      target.clear();
      return;
    }
    target.set(parsed.x, parsed.y, parsed.z, result.code, result.servoAngles, result.zone);
  });
  useEffect(() => () => target.clear(), [target]);

  // A click on the floor sets X and Y.
  useEffect(
    () =>
      target.onPlace((x, y) => {
        setEdited((f) => ({ ...(f ?? start), x: String(x), y: String(y) }));
        setRefusal('');
      }),
    [target, start],
  );

  const live = useSampled(() => ({
    enabled: link.mayMove && store.connection === 'connected' && !store.isStale(performance.now()),
    replies: store.kmsReplies,
    reply: store.kmsReply,
  }));

  const edit = (key: keyof TargetFields) => (e: React.ChangeEvent<HTMLInputElement>) => {
    setEdited({ ...fields, [key]: e.currentTarget.value });
    setRefusal('');
  };

  const move = () => {
    if (!parsed.ok) return setRefusal(`Not sent: ${parsed.error}`);
    if (!result || result.code !== 0) {
      return setRefusal(
        `Not sent: ${ikCodeMessage(result?.code ?? 2)} (code ${result?.code ?? 2}).`,
      );
    }
    setRefusal('');
    if (result.via === 'request') {
      const t = { x: parsed.x, y: parsed.y, z: parsed.z };
      const targets = [parsed.pitch === undefined ? t : { ...t, pitch: parsed.pitch }];
      const id = nextRequestId();
      if (
        !link.mayMove ||
        !robots.fleet.request(
          { id, mode: 'joint', targets, execute: true },
          link.control.requestTopic,
        )
      )
        return setRefusal('Not sent: the broker is not connected.');
      requests.sent(id, `move to ${parsed.x} ${parsed.y} ${parsed.z}`);
      setSent({
        text: `(${parsed.x}, ${parsed.y}, ${parsed.z}) as a motion request`,
        replies: Infinity,
      });
      return;
    }
    link.moveTo(parsed.x, parsed.y, parsed.z, parsed.pitch, result.pwm);
    setSent({ text: `(${parsed.x}, ${parsed.y}, ${parsed.z})`, replies: live.replies });
  };

  const replied = sent !== null && live.replies > sent.replies && live.reply !== null;
  const preview = !touched
    ? 'Enter a target, or click the floor to place one.'
    : !parsed.ok
      ? parsed.error
      : result!.code === 0
        ? `Reachable at pitch ${result!.alpha.toFixed(0)}° — the ghost shows the pose.`
        : `Unreachable: ${ikCodeMessage(result!.code)} (code ${result!.code}).`;

  return (
    <section className="panel cartesian" aria-labelledby="cartesian-title">
      <h2 id="cartesian-title">Cartesian target</h2>
      <form
        className="xyz"
        onSubmit={(e) => {
          e.preventDefault();
          move();
        }}
      >
        {CART_FIELDS.map(([key, label]) => (
          <label className="field small" key={key}>
            <span>{label}</span>
            <input
              type="number"
              step="any"
              value={fields[key]}
              onChange={edit(key)}
              {...(key === 'pitch'
                ? { placeholder: 'auto' }
                : { 'aria-describedby': 'cart-units' })}
            />
          </label>
        ))}
        <button type="submit" disabled={!live.enabled}>
          Move
        </button>
      </form>
      <p id="cart-units" className="dim small-print">
        mm, z up from the floor; pitch in degrees (−90 = pointing down), blank = auto. Click the
        floor to place X, Y.
      </p>
      <p
        className={`note ${!touched ? 'dim' : !parsed.ok || result!.code !== 0 ? 'bad' : 'ok'}`}
        role="status"
        data-testid="ik-preview"
      >
        {preview}
      </p>
      {refusal && (
        <p className="note bad" role="alert" data-testid="kms-refusal">
          {refusal}
        </p>
      )}
      {sent && (
        <p className="note" role="status" data-testid="kms-reply">
          {sent.replies === Infinity
            ? `Sent ${sent.text}; its feedback: Command panel.`
            : replied
              ? `Arm replied to ${sent.text}: code ${live.reply} — ${ikCodeMessage(live.reply!)}.`
              : `Sent ${sent.text}; waiting for the arm's reply…`}
        </p>
      )}
    </section>
  );
}
