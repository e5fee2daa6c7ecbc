/**
 * The Zones section's form as strings, and the zone it describes (pure): one number field per
 * coordinate of the chosen shape. A blank or non-number field is named in the message; the
 * rest (min below max, a non-zero normal, a unique name) is the profile parser's to say, on
 * the server, by zone and field.
 */
import type { Zone, ZoneShape } from '@armtwin/robot';

/** The number fields of each shape, in the order the form shows them. */
export const SHAPE_FIELDS: Record<ZoneShape, readonly string[]> = {
  box: ['min x', 'min y', 'min z', 'max x', 'max y', 'max z'],
  cylinder: ['centre x', 'centre y', 'radius', 'z min', 'z max'],
  plane: ['point x', 'point y', 'point z', 'normal x', 'normal y', 'normal z'],
};

export type ZoneFromFields = { ok: true; zone: Zone } | { ok: false; error: string };

export function zoneFromFields(
  name: string,
  shape: ZoneShape,
  values: Readonly<Record<string, string>>,
): ZoneFromFields {
  if (!name.trim()) return { ok: false, error: 'Give the zone a name.' };
  const n: number[] = [];
  for (const field of SHAPE_FIELDS[shape]) {
    const text = (values[field] ?? '').trim();
    const v = Number(text);
    if (text === '' || !Number.isFinite(v))
      return { ok: false, error: `${field}: a number in mm, please.` };
    n.push(v);
  }
  const z = name.trim();
  switch (shape) {
    case 'box':
      return {
        ok: true,
        zone: { name: z, shape, min: [n[0]!, n[1]!, n[2]!], max: [n[3]!, n[4]!, n[5]!] },
      };
    case 'cylinder':
      return {
        ok: true,
        zone: { name: z, shape, center: [n[0]!, n[1]!], radius: n[2]!, zMin: n[3]!, zMax: n[4]! },
      };
    case 'plane':
      return {
        ok: true,
        zone: { name: z, shape, point: [n[0]!, n[1]!, n[2]!], normal: [n[3]!, n[4]!, n[5]!] },
      };
    default: {
      const never: never = shape;
      return never;
    }
  }
}

/** One line about a zone: `box 150…400 × −150…150 × −20…30 mm`. */
export function describeZone(zone: Zone): string {
  switch (zone.shape) {
    case 'box':
      return `box ${zone.min.map((v, i) => `${v}…${zone.max[i]}`).join(' × ')} mm`;
    case 'cylinder':
      return `cylinder r ${zone.radius} at (${zone.center.join(', ')}), z ${zone.zMin}…${zone.zMax} mm`;
    case 'plane':
      return `plane through (${zone.point.join(', ')}), out along (${zone.normal.map((v) => Math.round(v * 100) / 100).join(', ')})`;
    default: {
      const never: never = zone;
      return never;
    }
  }
}
