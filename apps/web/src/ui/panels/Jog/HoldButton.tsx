/**
 * A hold-to-move button (− or + of one joint): the joint moves while a pointer or finger holds
 * it down, and stops when it is lifted, cancelled or leaves the button (../../../core/jog/HoldJog.ts). At least
 * 44 px square, for a finger.
 */
import type { HoldJog, JogTarget } from '../../../core/jog/HoldJog.ts';

interface Props {
  hold: HoldJog;
  /** A joint's index, or a tip axis. */
  index: JogTarget;
  rate: 1 | -1;
  /** The joint's name (or `tip x`), for the accessible label. */
  name: string;
  disabled: boolean;
}

export function HoldButton({ hold, index, rate, name, disabled }: Props) {
  const input = `pointer:${index}:${rate}`;
  const letGo = () => hold.release(input);
  return (
    <button
      type="button"
      className="jog-hold"
      disabled={disabled}
      aria-label={`Hold ${name} ${rate > 0 ? '+' : '−'}`}
      data-testid={`hold-${index}-${rate > 0 ? 'plus' : 'minus'}`}
      onPointerDown={(e) => {
        if (e.button !== 0) return;
        e.preventDefault();
        hold.press(input, index, rate);
      }}
      onPointerUp={letGo}
      onPointerCancel={letGo}
      onPointerLeave={letGo}
      onLostPointerCapture={letGo}
      onContextMenu={(e) => e.preventDefault()}
      onBlur={letGo}
    >
      {rate > 0 ? '+' : '−'}
    </button>
  );
}
