/**
 * Tracking error per joint (./trackingError.ts): the reported angle against the command's course
 * at the same instant; without a course seen, against this HUD's commanded pulse once the joint
 * has stopped moving.
 */
import { angleFromPwm } from '@armtwin/protocol';
import type { ArmProfile } from '@armtwin/ik';
import type { TrackingErrors } from './trackingError.ts';
import type { TwinPredictor } from './TwinPredictor.ts';

export function trackJoints(
  tracking: TrackingErrors,
  predictor: Pick<TwinPredictor, 'joint'>,
  servos: ArmProfile['servos'],
  commandedPwm: Float64Array,
  angle: Float64Array,
): void {
  for (let i = 0; i < angle.length; i++) {
    const j = predictor.joint(i);
    if (!j) continue;
    let commanded = j.commandedAt(j.s0);
    const pwm = commandedPwm[i]!;
    if (Number.isNaN(commanded) && Number.isFinite(pwm) && j.reportVelocity() === 0)
      commanded = angleFromPwm(pwm, servos[i]!.polarity);
    tracking.set(i, commanded, angle[i]!);
  }
}
