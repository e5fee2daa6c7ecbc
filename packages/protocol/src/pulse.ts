import { PWM_CENTRE, PWM_MAX, PWM_MIN, US_PER_DEG } from './limits.ts';

/** Mounting polarity of a servo: +1 or −1. */
export type Polarity = 1 | -1;

/** Pulse width (µs, rounded) for servo angle `deg` relative to centre. Not clamped. */
export const pwmFromAngle = (deg: number, polarity: Polarity = 1): number =>
  Math.round(PWM_CENTRE + (polarity * deg * US_PER_DEG));

/** Servo angle (degrees relative to centre) for a pulse width. */
export const angleFromPwm = (pwm: number, polarity: Polarity = 1): number =>
  (polarity * (pwm - PWM_CENTRE)) / US_PER_DEG;

/** 0 … 1 across the pulse range, for display. */
export const normalisedPwm = (pwm: number): number => (pwm - PWM_MIN) / (PWM_MAX - PWM_MIN);
