/**
 * The controller as every gateway builds it (`@armtwin/controller/mqtt`): the core on a driver,
 * the control input in front of it (reader, payload bound, rate limit) and the operator-topic
 * deadman (./deadman.ts) that stops a moving arm through the core. One home for this wiring, so
 * the bus, the ROS 2 and the LSC gateway cannot drift apart. Pure: the timers come with `io`.
 */
import type { OperatorTimers, OperatorWatch } from '@armtwin/protocol';
import { ControlInput, type CommandRunner } from './control-input.ts';
import { ControllerCore, type ControllerRules } from './core.ts';
import { operatorDeadman } from './deadman.ts';
import type { ControllerDriver } from './driver.ts';
import type { Joint } from './joints.ts';

export interface DriverControlIo extends OperatorTimers {
  /** The driver's clock, ms. */
  now(): number;
  /** Told the first time each kind of problem happens. */
  onFirst(kind: string, message: string): void;
}

export interface DriverControlOptions {
  /** A beating operator is let go after this long without a `1`, ms (0 = only a `0`). */
  operatorLeaseMs: number;
  /** The deadman stopped the arm: its replies (`$ERR:deadman stop!`), to publish. */
  deadmanStopped(replies: string[]): void;
  /**
   * What the control input hands admitted commands to (default: the core itself); the LSC
   * gateway puts its firmware gate here, which asks the core and passes reads on.
   */
  runner?(core: ControllerCore): CommandRunner;
}

export interface DriverControl {
  /** The controller: frames in, goals to the driver out. */
  readonly controller: ControllerCore;
  /** The control input in front of it. */
  readonly input: ControlInput;
  /** The deadman on `arm/{id}/operator`. */
  readonly operator: OperatorWatch;
}

export function driverControl(
  joints: readonly Joint[],
  driver: ControllerDriver,
  rules: ControllerRules,
  io: DriverControlIo,
  o: DriverControlOptions,
): DriverControl {
  const controller = new ControllerCore(joints, driver, rules);
  const input = new ControlInput(
    o.runner?.(controller) ?? controller,
    { onFirst: io.onFirst },
    io.now(),
  );
  const operator = operatorDeadman(
    io,
    () => {
      const out: string[] = [];
      if (!controller.operatorLeft(io.now(), out)) return false;
      o.deadmanStopped(out);
      return true;
    },
    io.onFirst,
    o.operatorLeaseMs,
  );
  return { controller, input, operator };
}
