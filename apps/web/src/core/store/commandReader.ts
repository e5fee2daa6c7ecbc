/**
 * Commands seen on the arm's control topics (this page's own and, where the broker lets the page
 * read them, everyone's), read into the predictor's idea of where each joint is heading: a move
 * (pulse or angle) sets a joint's course, a stop ends one joint's or, for id 255, every joint's.
 */
import { angleFromPwm, createReader, type Frame, type Reader } from '@armtwin/protocol';
import type { ArmProfile } from '@armtwin/ik';
import type { TwinPredictor } from './TwinPredictor.ts';

/**
 * A reader of control payloads; `arm` and `now` are read per frame (they change). `slot` is the
 * profile index of the servo a frame names by id (-1: none), as the store keeps it.
 */
export function createCommandReader(
  predictor: Pick<TwinPredictor, 'command' | 'stop'>,
  arm: () => ArmProfile,
  slot: (id: number) => number,
  now: () => number,
): Reader {
  const onCommand = (f: Frame): void => {
    if (f.type === 'stop' && f.id === 255) return predictor.stop(undefined, now());
    if (f.type !== 'move' && f.type !== 'angleMove' && f.type !== 'stop') return;
    const i = slot(f.id);
    if (i < 0) return;
    if (f.type === 'move')
      predictor.command(i, angleFromPwm(f.pwm, arm().servos[i]!.polarity), f.ms, now());
    else if (f.type === 'angleMove') predictor.command(i, f.deg, f.ms, now());
    else predictor.stop(i, now());
  };
  return createReader({
    onFrame: onCommand,
    onGroup: (g) => {
      for (const f of g.frames) onCommand(f);
    },
  });
}
