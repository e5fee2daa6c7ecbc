/**
 * The users-and-roles file, Mosquitto-compatible password hashes and the role rules. Pure; the
 * brokers themselves are tested in tests/integration/auth-*.test.ts with the same role table.
 */
import { describe, expect, test } from 'vitest';
import { hashPassword, isPasswordHash, verifyPassword } from '../src/password.ts';
import {
  canPublish,
  canSubscribe,
  filterWithin,
  topicMatches,
  type Principal,
} from '../src/roles.ts';
import { parseUsers } from '../src/users.ts';

/** Written by `mosquitto_passwd -b -c f alice 'correct horse'` (Mosquitto 2.0.11). */
const MOSQUITTO_HASH =
  '$7$101$fsy52yhS04GcvdzP$eE0c9X5+C8dVspoFhZPfD3vc8RFdsJCtFluoi6MRl/EHV/OvI4rPbwA+d9DYIE29gtIfiDgTR37obRN6j+PNlg==';

describe('password hashes (Mosquitto $7$)', () => {
  test('verifies what mosquitto_passwd wrote', () => {
    expect(verifyPassword('correct horse', MOSQUITTO_HASH)).toBe(true);
    expect(verifyPassword('correct horsE', MOSQUITTO_HASH)).toBe(false);
  });

  test('writes $7$<iterations>$<salt>$<key> and verifies it; a fixed salt gives a fixed hash', () => {
    const h = hashPassword('s3cret', { iterations: 1000 });
    expect(h).toMatch(/^\$7\$1000\$[A-Za-z0-9+/]{16}\$[A-Za-z0-9+/]{86}==$/);
    expect(verifyPassword('s3cret', h)).toBe(true);
    expect(verifyPassword('s3cret!', h)).toBe(false);
    const salt = Buffer.alloc(12, 7);
    expect(hashPassword('x', { iterations: 101, salt })).toBe(
      hashPassword('x', { iterations: 101, salt }),
    );
  });

  test('anything else is not a hash and never verifies', () => {
    for (const bad of ['', 'plain', '$7$abc$x$y', '$7$101$c2FsdA==$c2hvcnQ=', '$1$x$y'])
      expect([isPasswordHash(bad), verifyPassword('plain', bad)]).toEqual([false, false]);
  });
});

describe('topic matching', () => {
  test.each([
    ['arm/+/status', 'arm/arm1/status', true],
    ['arm/+/status', 'arm/arm1/status/x', false],
    ['arm/#', 'arm/a/b/c', true],
    ['#', '$SYS/broker', false],
  ])('%s matches %s: %s', (f, t, want) => expect(topicMatches(f, t)).toBe(want));

  test.each([
    ['arm/+/status', 'arm/+/status', true],
    ['arm/arm1/status', 'arm/+/status', true],
    ['arm/#', 'arm/+/status', false],
    ['#', 'arm/+/status', false],
    ['arm/+/+', 'arm/+/status', false],
    ['arm/+/status', 'arm/arm1/status', false],
  ])('subscription %s within rule %s: %s', (s, r, want) => expect(filterWithin(s, r)).toBe(want));
});

describe('roles', () => {
  const viewer: Principal = { name: 'v', role: 'viewer' };
  const operator: Principal = { name: 'o', role: 'operator' };
  const device: Principal = { name: 'd', role: 'device', arm: 'arm1' };
  const mw: Principal = { name: 'm', role: 'middleware' };

  test('viewer reads, never writes', () => {
    expect(canSubscribe(viewer, 'arm/+/status')).toBe(true);
    expect(canSubscribe(viewer, 'arm/+/operator')).toBe(true);
    expect(canSubscribe(viewer, 'arm/+/control')).toBe(false);
    expect(canPublish(viewer, 'arm/arm1/control')).toBe(false);
  });

  test('operator adds its own control and claim topics, operator, request and sim', () => {
    for (const k of [
      `control/${operator.name}`,
      `claim/${operator.name}`,
      'operator',
      'request',
      'sim',
    ])
      expect(canPublish(operator, `arm/arm7/${k}`)).toBe(true);
    // One operator at a time (docs/protocol.md § Control): not the plain control topic, nobody
    // else's, and no take-over (that is an admin's).
    expect(canPublish(operator, 'arm/arm7/control')).toBe(false);
    expect(canPublish(operator, 'arm/arm7/control/someone-else')).toBe(false);
    expect(canPublish(operator, `arm/arm7/override/${operator.name}`)).toBe(false);
    expect(canPublish({ name: 'root', role: 'admin' }, 'arm/arm7/override/root')).toBe(true);
    expect(canPublish({ name: 'root', role: 'admin' }, 'arm/arm7/override/alice')).toBe(false);
    expect(canPublish(operator, 'arm/arm7/status')).toBe(false);
    expect(canPublish(operator, 'arm/arm7/sim/faults')).toBe(false);
  });

  test("an operator's leader arm announces only its own pose and state, and only they re-enable it", () => {
    for (const k of ['', '/state', '/enable'])
      expect(canPublish(operator, `arm/arm7/leader/${operator.name}${k}`)).toBe(true);
    expect(canPublish(operator, 'arm/arm7/leader/someone-else/enable')).toBe(false);
    expect(canPublish(viewer, `arm/arm7/leader/${operator.name}`)).toBe(false);
    expect(canSubscribe(viewer, 'arm/+/leader/+')).toBe(true);
    expect(canSubscribe(viewer, 'arm/+/leader/+/state')).toBe(true);
  });

  test('a device is confined to its own arm', () => {
    expect(canPublish(device, 'arm/arm1/status')).toBe(true);
    expect(canPublish(device, 'arm/arm2/status')).toBe(false);
    expect(canSubscribe(device, 'arm/arm1/control')).toBe(true);
    expect(canSubscribe(device, 'arm/+/control')).toBe(false);
    expect(canSubscribe(device, 'arm/arm1/status')).toBe(false);
  });

  test("viewers, operators and the middleware (to record and show) read the cameras; a device announces only its own arm's", () => {
    for (const p of [viewer, operator]) {
      expect(canSubscribe(p, 'arm/+/camera/+')).toBe(true);
      expect(canSubscribe(p, 'arm/arm1/camera/front')).toBe(true);
      expect(canPublish(p, 'arm/arm1/camera/front')).toBe(false);
    }
    expect(canPublish(device, 'arm/arm1/camera/front')).toBe(true);
    expect(canPublish(device, 'arm/arm2/camera/front')).toBe(false);
    expect(canPublish(device, 'arm/arm1/camera/front/x')).toBe(false);
    // the middleware records the cameras and its Foxglove server shows them; it never announces
    expect(canSubscribe(mw, 'arm/+/camera/+')).toBe(true);
    expect(canPublish(mw, 'arm/arm1/camera/front')).toBe(false);
  });

  test('an operator writes a camera calibration; a viewer reads it, a device does neither', () => {
    const topic = 'arm/arm1/camera/front/calibration';
    expect(canPublish(operator, topic)).toBe(true);
    expect(canPublish(viewer, topic)).toBe(false);
    expect(canPublish(device, topic)).toBe(false);
    for (const p of [viewer, operator])
      expect(canSubscribe(p, 'arm/arm1/camera/+/calibration')).toBe(true);
    expect(canSubscribe(mw, 'arm/+/camera/+/calibration')).toBe(false);
  });

  test("an operator turns a bus arm's torque off and on; only that arm's device hears it", () => {
    expect(canPublish(operator, 'arm/arm1/torque')).toBe(true);
    expect(canPublish(viewer, 'arm/arm1/torque')).toBe(false);
    expect(canSubscribe(device, 'arm/arm1/torque')).toBe(true);
    expect(canSubscribe(device, 'arm/arm2/torque')).toBe(false);
  });

  test('middleware reads status and control, also through $share', () => {
    expect(canSubscribe(mw, '$share/g1/arm/+/status')).toBe(true);
    expect(canSubscribe(mw, '$share/g1/arm/+/control')).toBe(true);
    expect(canSubscribe(mw, '$share/g1/#')).toBe(false);
    expect(canPublish(mw, 'arm/arm1/status')).toBe(false);
  });
});

describe('users file', () => {
  const h = hashPassword('pw', { iterations: 10 });
  const file = (users: unknown[]) => JSON.stringify({ users });

  test('parses, authenticates, and gives the device its arm', () => {
    const u = parseUsers(file([{ name: 'arm1', role: 'device', arm: 'arm1', password: h }]));
    expect(u.authenticate('arm1', 'pw')).toEqual({ name: 'arm1', role: 'device', arm: 'arm1' });
    expect(u.authenticate('arm1', 'nope')).toBeNull();
    expect(u.authenticate('ghost', 'pw')).toBeNull();
  });

  test.each([
    ['a device without its arm', [{ name: 'd', role: 'device', password: h }], /arm/],
    ['an arm on a viewer', [{ name: 'v', role: 'viewer', arm: 'arm1', password: h }], /arm/],
    ['a plain-text password', [{ name: 'v', role: 'viewer', password: 'pw' }], /password/],
    ['a bad name', [{ name: 'a b', role: 'viewer', password: h }], /name/],
    ['an unknown role', [{ name: 'r', role: 'root', password: h }], /role/],
    ['a bad arm id', [{ name: 'd', role: 'device', arm: 'Arm 1', password: h }], /arm/],
    [
      'a duplicate',
      [
        { name: 'v', role: 'viewer', password: h },
        { name: 'v', role: 'viewer', password: h },
      ],
      /unique/,
    ],
  ])('refuses %s', (_name, users, msg) => expect(() => parseUsers(file(users))).toThrow(msg));
});
