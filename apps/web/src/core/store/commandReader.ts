/**
 * Commands seen on the arm's control topics (this page's own and, where the broker lets the page
 * read them, everyone's), read into the predictor's idea of where each joint is heading: a move
 * (pulse or angle) sets a joint's course, a stop ends one joint's or, for id 255, every joint's.
 */
import { angleFromPwm, createReader, type Frame, type Reader } from '@armtwin/protocol';
import type { ArmProfile } from '@armtwin/ik';
import type { TwinPredictor } from './TwinPredictor.ts';

/** A reader of control payloads; `arm` and `now` are read per frame (they change). */
export function createCommandReader(
  predictor: Pick<TwinPredictor, 'command' | 'stop'>,
  arm: () => ArmProfile,
  now: () => number,
): Reader {
  const onCommand = (f: Frame): void => {
    const servos = arm().servos;
    if (f.type === 'move' && f.id < servos.length)
      predictor.command(f.id, angleFromPwm(f.pwm, servos[f.id]!.polarity), f.ms, now());
    else if (f.type === 'angleMove' && f.id < servos.length)
      predictor.command(f.id, f.deg, f.ms, now());
    else if (f.type === 'stop') predictor.stop(f.id === 255 ? undefined : f.id, now());
  };
  return createReader({
    onFrame: onCommand,
    onGroup: (g) => {
      for (const f of g.frames) onCommand(f);
    },
  });
}
