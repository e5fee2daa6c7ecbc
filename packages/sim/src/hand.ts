/**
 * A hand on an emulated servo bus (`armtwin sim --bus … --hand`): lines on stdin such as
 * `1:30,2:-15.5` put servo 1's shaft at +30° and servo 2's at −15.5° (servo angles as the bus
 * gateway reads them: 0° at tick 2048, the profile's polarity), as a hand turns a servo whose
 * torque is off (a leader arm). A servo with torque on goes back to its goal, as a real one
 * would. Pure: parsing only; `BusSimCore.hand` moves the shaft.
 */

export interface HandMove {
  id: number;
  degrees: number;
}

const MOVE = /^(\d{1,3}):([+-]?\d+(?:\.\d+)?)$/;

/** The moves of one line (`ID:DEGREES[,ID:DEGREES…]`); throws saying what is wrong. */
export function parseHandLine(line: string): HandMove[] {
  const text = line.trim();
  if (!text) return [];
  return text.split(/[,\s]+/).map((part) => {
    const m = MOVE.exec(part);
    if (!m)
      throw new Error(`hand: ${JSON.stringify(part).slice(0, 40)} is not ID:DEGREES (e.g. 1:30.5)`);
    const id = Number(m[1]);
    const degrees = Number(m[2]);
    if (id > 253) throw new Error(`hand: servo id ${id} is not 0-253`);
    if (Math.abs(degrees) > 3600) throw new Error(`hand: ${degrees}° is past ±3600°`);
    return { id, degrees };
  });
}
