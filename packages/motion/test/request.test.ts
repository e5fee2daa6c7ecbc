/** Motion requests: the validator names the first bad field; the command box makes requests. */
import { describe, expect, it } from 'vitest';
import { MAX_REQUEST_BYTES, parseCommand, parseRequest, validateRequest } from '../src/index.ts';
import { loadRobot } from './fixtures.ts';

const ok = { id: 'r1', mode: 'joint', targets: ['home'] };

describe('validateRequest', () => {
  it('accepts every kind of target', () => {
    const r = validateRequest({
      ...ok,
      targets: [
        'ready',
        { x: 150, y: 0, z: 80 },
        { x: 1, y: 2, z: 3, pitch: -90 },
        { unit: 'servo', servos: { '001': -30 } },
      ],
      execute: true,
      speed: 0.3,
      linearSpeed: 50,
    });
    expect(r.ok).toBe(true);
  });

  it.each([
    [{ ...ok, extra: 1 }, 'extra', /unknown field/],
    [{ ...ok, id: 'has space' }, 'id', /required/],
    [{ mode: 'joint', targets: ['home'] }, 'id', /required/],
    [{ ...ok, mode: 'fly' }, 'mode', /"joint" or "cartesian"/],
    [{ ...ok, targets: [] }, 'targets', /empty/],
    [{ ...ok, targets: new Array(65).fill('home') }, 'targets', /at most 64/],
    [{ ...ok, targets: 'home' }, 'targets', /array/],
    [{ ...ok, targets: ['home', { x: 1, y: 'a', z: 3 }] }, 'targets[1].y', /finite number/],
    [{ ...ok, targets: [{ x: 1, y: 2 }] }, 'targets[0].z', /finite number/],
    [{ ...ok, targets: [{ x: 1, y: 2, z: 3, roll: 4 }] }, 'targets[0].roll', /unknown field/],
    [{ ...ok, targets: [{ x: 1e9, y: 2, z: 3 }] }, 'targets[0].x', /outside/],
    [{ ...ok, targets: [{ x: 1, y: 2, z: 3, pitch: 200 }] }, 'targets[0].pitch', /outside/],
    [{ ...ok, targets: [{ servos: { '1': 1500 } }] }, 'targets[0].servos.1', /three digits/],
    [{ ...ok, targets: [{ servos: {} }] }, 'targets[0].servos', /empty/],
    [{ ...ok, targets: [{ unit: 'rad', servos: { '001': 1 } }] }, 'targets[0].unit', /"us"/],
    [{ ...ok, targets: ['Home!'] }, 'targets[0]', /pose name/],
    [{ ...ok, execute: 'yes' }, 'execute', /true or false/],
    [{ ...ok, speed: 0 }, 'speed', /outside \(0, 1\]/],
    [[1, 2], '(request)', /object/],
  ])('refuses %j naming %s', (json, field, message) => {
    const r = validateRequest(json);
    expect(r.ok).toBe(false);
    if (r.ok) return;
    expect(r.field).toBe(field);
    expect(r.message).toMatch(message);
    expect(r.message.startsWith(`${field}: `)).toBe(true);
  });

  it('keeps the id of an otherwise bad request, so its feedback can be matched', () => {
    const r = validateRequest({ id: 'abc', mode: 'x', targets: [] });
    expect(r).toMatchObject({ ok: false, id: 'abc', field: 'mode' });
  });

  it('parseRequest refuses non-JSON and oversized payloads', () => {
    expect(parseRequest('nope')).toMatchObject({ ok: false, message: '(request): not JSON' });
    expect(parseRequest('x'.repeat(MAX_REQUEST_BYTES + 1))).toMatchObject({
      ok: false,
      field: '(request)',
    });
    expect(parseRequest(new TextEncoder().encode(JSON.stringify(ok)))).toMatchObject({ ok: true });
  });
});

describe('parseCommand', () => {
  const a5 = loadRobot('armtwin5').profile;
  const t6 = loadRobot('track6').profile;

  it.each([
    ['home', { mode: 'joint', targets: ['home'], execute: true }],
    ['  Ready ', { mode: 'joint', targets: ['ready'], execute: true }],
    ['go to rest', { mode: 'joint', targets: ['rest'], execute: true }],
    ['open gripper', { mode: 'joint', targets: ['open'], execute: true }],
    ['close gripper', { mode: 'joint', targets: ['closed'], execute: true }],
    ['move to 150 0 80', { mode: 'joint', targets: [{ x: 150, y: 0, z: 80 }], execute: true }],
    [
      'move to 150, 0, 80 pitch -90',
      { mode: 'joint', targets: [{ x: 150, y: 0, z: 80, pitch: -90 }], execute: true },
    ],
    [
      'line to -12.5 180 40',
      { mode: 'cartesian', targets: [{ x: -12.5, y: 180, z: 40 }], execute: true },
    ],
    [
      'plan move to 150 0 80',
      { mode: 'joint', targets: [{ x: 150, y: 0, z: 80 }], execute: false },
    ],
  ])('%s', (text, expected) => {
    expect(parseCommand(text, 'c1', a5)).toEqual({ ok: true, request: { id: 'c1', ...expected } });
  });

  it('refuses what it cannot read, and poses the arm lacks', () => {
    expect(parseCommand('move to 1 2', 'c', a5)).toMatchObject({
      ok: false,
      message: /not a command/,
    });
    expect(parseCommand('', 'c')).toMatchObject({ ok: false, message: 'empty command' });
    expect(parseCommand('open gripper', 'c', t6)).toMatchObject({
      ok: false,
      message: /track6 has no gripper pose "open"/,
    });
    expect(parseCommand('dance', 'c', a5)).toMatchObject({ ok: false, message: /no pose "dance"/ });
    expect(parseCommand('side', 'c', t6)).toMatchObject({ ok: true });
  });
});
