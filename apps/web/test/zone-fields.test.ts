/**
 * The Zones section's form (panels/Zones/zoneFields.ts): each shape's numbers become the zone
 * the profile declares; a blank or non-number field is named, and nothing is built.
 */
import { describe, expect, test } from 'vitest';
import { describeZone, zoneFromFields } from '../src/core/zones/zoneFields.ts';

describe('zone form', () => {
  test('box, cylinder and plane from their fields', () => {
    expect(
      zoneFromFields(' table ', 'box', {
        'min x': '150',
        'min y': '-150',
        'min z': '-20',
        'max x': '400',
        'max y': '150',
        'max z': '30',
      }),
    ).toEqual({
      ok: true,
      zone: { name: 'table', shape: 'box', min: [150, -150, -20], max: [400, 150, 30] },
    });
    const post = zoneFromFields('post', 'cylinder', {
      'centre x': '0',
      'centre y': '250',
      radius: '30',
      'z min': '0',
      'z max': '600',
    });
    expect(post).toEqual({
      ok: true,
      zone: { name: 'post', shape: 'cylinder', center: [0, 250], radius: 30, zMin: 0, zMax: 600 },
    });
    if (post.ok) expect(describeZone(post.zone)).toBe('cylinder r 30 at (0, 250), z 0…600 mm');
    const side = zoneFromFields('operator side', 'plane', {
      'point x': '0',
      'point y': '-300',
      'point z': '0',
      'normal x': '0',
      'normal y': '-1',
      'normal z': '0',
    });
    expect(side).toMatchObject({ ok: true, zone: { point: [0, -300, 0], normal: [0, -1, 0] } });
  });

  test('a blank name or a field that is not a number is named, and no zone is built', () => {
    expect(zoneFromFields('', 'box', {})).toEqual({ ok: false, error: 'Give the zone a name.' });
    expect(zoneFromFields('t', 'box', { 'min x': '1', 'min y': 'ten' })).toEqual({
      ok: false,
      error: 'min y: a number in mm, please.',
    });
  });
});
