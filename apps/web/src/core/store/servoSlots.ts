/**
 * Where a servo's values live in the store's per-servo arrays: its index in the profile, found
 * from the id a frame names. Ids are the profile's own and need not start at 0 or be
 * contiguous (armtwin5: 000–005 → 0–5; the SO-101, as LeRobot numbers its Feetech bus:
 * 001–006 → 0–5).
 */

/** Frame id (0–254) → the servo's index in `servos`, or -1 for an id the arm does not have. */
export function servoSlots(servos: readonly { readonly id: number }[]): Int16Array {
  const slots = new Int16Array(256).fill(-1);
  servos.forEach((s, i) => {
    if (Number.isInteger(s.id) && s.id >= 0 && s.id < slots.length) slots[s.id] = i;
  });
  return slots;
}
