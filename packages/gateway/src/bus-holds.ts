/**
 * The bus gateway's steps that put the goals where the servos are (./bus-gateway.ts holds one):
 * the hold (a stop, the e-stop, the deadman: goals = present positions, ahead of any queued goal),
 * the set-up of servos found at line open or back after being lost (torque off, multi-turn, hold,
 * torque on as wanted), and torque on or off from `arm/{id}/torque` (on: a hold first). A servo
 * whose read is missed holds where it was last read: torque never comes on over a stale goal.
 */
import type { BusProtocol, ServoCalibration } from '@armtwin/servo-bus';
import type { BusLine } from './bus-line.ts';
import type { BusReports } from './bus-reports.ts';
import type { BusJoint } from './bus-servos.ts';
import { goalsWrite, multiTurnWrites } from './bus-writes.ts';

/** What the steps use of their gateway. */
export interface BusHoldsGateway {
  readonly protocol: BusProtocol;
  readonly line: BusLine;
  readonly reports: BusReports;
  /** Servos that answer. */
  readonly found: ReadonlySet<number>;
  joint(id: number): BusJoint;
  /** A servo's zero and direction on the bus. */
  calibration(id: number): ServoCalibration;
}

export class BusHolds {
  /** Torque as `arm/{id}/torque` last asked (on at start). */
  torqueWanted = true;

  constructor(private readonly g: BusHoldsGateway) {}

  /** Stops `ids` where they are: goals = present positions, ahead of any queued goal. */
  hold(ids: number[]): void {
    this.g.line.dropGoals();
    this.holdThen(ids, () => {}, true);
  }

  /** Torque on (goals = present positions first) or off, for the servos found. */
  torque(on: boolean, ready: boolean): void {
    this.torqueWanted = on;
    if (!ready) return;
    const ids = [...this.g.found];
    if (on) this.holdThen(ids, () => this.g.line.torque(true, ids), true);
    else this.g.line.torque(false, ids, true);
  }

  /**
   * Torque off (at line open; not for a servo that comes back, which may only have missed
   * reads), multi-turn where needed (refused harmlessly by a servo whose torque is on), goals =
   * present positions, torque on (as wanted).
   */
  setUp(ids: number[], torqueOff = true): void {
    if (ids.length === 0) return;
    const line = this.g.line;
    if (torqueOff) line.torque(false, ids);
    for (const id of ids)
      if (this.g.joint(id).multiTurn)
        for (const w of multiTurnWrites(this.g.protocol)) line.config(id, w);
    this.holdThen(ids, () => this.torqueWanted && line.torque(true, ids), false);
  }

  /** Reads `ids`, writes their present positions as goals, then `then()`. */
  private holdThen(ids: number[], then: () => void, first: boolean): void {
    const g = this.g;
    const present = ids.filter((id) => g.found.has(id));
    if (present.length === 0) return then();
    g.line.readPositions(
      present,
      (r) => {
        // A servo whose read was missed holds where it was last read: torque must never come on
        // over a stale goal (one written while it was limp, say), which it would run to.
        const read = new Map(r.servos.map((s) => [s.id, s.degrees]));
        const goals = present.flatMap((id) => {
          const degrees = read.get(id) ?? g.reports.positions.get(id);
          if (degrees === undefined) return [];
          return [{ id, degrees, speedDegPerS: g.joint(id).servo.maxSpeed }];
        });
        g.reports.remember(goals);
        if (goals.length)
          g.line.send(
            goalsWrite(g.protocol, goals, (id) => g.calibration(id)),
            'hold',
            true,
          );
        then();
      },
      first,
    );
  }
}
