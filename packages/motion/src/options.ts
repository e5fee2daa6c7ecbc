/** Planning and execution options, and their defaults (declared once). */

export interface PlanOptions {
  /** Fraction of each servo's speed limit (profile `maxSpeed`) a plan may use, (0, 1]. */
  speed: number;
  /** Joint plans: `trapezoid` (ramps up and down, all axes finishing together) or `linear` (constant speed, synchronised). */
  profile: 'trapezoid' | 'linear';
  /** Time to reach top speed from rest, ms (trapezoid ramps; the Cartesian speed ramp). */
  accelMs: number;
  /** Joint plans: one sample every this many ms. */
  stepMs: number;
  /** Cartesian plans: tip speed along the path, mm/s (slower where a joint's limit demands). */
  linearSpeed: number;
  /** Cartesian plans: an IK step every this many mm (lengthened so no plan exceeds `maxSteps`). */
  stepMm: number;
  /** Cartesian plans: a pitch change alone gets a step every this many degrees. */
  stepDeg: number;
  /** Cartesian plans: at most this many IK steps in all. */
  maxSteps: number;
}

export const DEFAULT_PLAN_OPTIONS: Readonly<PlanOptions> = {
  speed: 0.5,
  profile: 'trapezoid',
  accelMs: 250,
  stepMs: 20,
  linearSpeed: 100,
  stepMm: 5,
  stepDeg: 2,
  maxSteps: 2000,
};

export interface ExecuteOptions {
  /** A move is streamed every this many ms (each move runs to the plan's pose one step later). */
  stepMs: number;
  /** Pose checking: a revolute servo further than this from the plan, degrees, pauses execution. */
  thresholdDeg: number;
  /** … a prismatic axis further than this, mm. */
  thresholdMm: number;
  /** How long the arm holds still after a pause before re-planning from where it is, ms. */
  pauseMs: number;
  /** Re-plans allowed in one execution; one more deviation fails it. */
  maxReplans: number;
}

export const DEFAULT_EXECUTE_OPTIONS: Readonly<ExecuteOptions> = {
  stepMs: 20,
  thresholdDeg: 5,
  thresholdMm: 20,
  pauseMs: 500,
  maxReplans: 3,
};
