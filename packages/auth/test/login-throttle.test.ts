import { afterEach, beforeEach, describe, expect, test, vi } from 'vitest';
import { hashPassword } from '../src/password.ts';
import { LoginThrottle } from '../src/throttle.ts';
import { parseUsers, type Users } from '../src/users.ts';

const OPTS = { perUser: 3, perAddress: 5, windowS: 60, lockoutS: 300 };

/** Users whose `authenticate` calls are counted: a locked-out attempt must not hash at all. */
function countedUsers() {
  const users = parseUsers(
    JSON.stringify({
      users: [
        { name: 'alice', role: 'operator', password: hashPassword('right', { iterations: 10 }) },
      ],
    }),
  );
  let checks = 0;
  const counted: Users = {
    list: users.list,
    authenticate: (n, p) => (checks++, users.authenticate(n, p)),
  };
  return { users: counted, checks: () => checks };
}

beforeEach(() => vi.useFakeTimers());
afterEach(() => vi.useRealTimers());

describe('failed log-ins are throttled', () => {
  test('the right password gets in; a few wrong ones are only refused', async () => {
    const { users } = countedUsers();
    const t = new LoginThrottle(users, OPTS);
    for (let i = 0; i < 3; i++)
      expect(await t.login('10.0.0.9', 'alice', 'wrong')).toEqual({ ok: false, lockedMs: 0 });
    expect(await t.login('10.0.0.9', 'alice', 'right')).toMatchObject({
      ok: true,
      principal: { name: 'alice', role: 'operator' },
    });
  });

  test('over the budget, the address is locked out for that user: even the right password, and no hashing', async () => {
    const { users, checks } = countedUsers();
    const t = new LoginThrottle(users, OPTS);
    for (let i = 0; i < 4; i++) await t.login('10.0.0.9', 'alice', 'wrong');
    const before = checks();
    const r = await t.login('10.0.0.9', 'alice', 'right');
    expect(r.ok).toBe(false);
    expect(!r.ok && r.lockedMs).toBeGreaterThan(290_000);
    expect(checks()).toBe(before);
    expect(t.counters).toEqual({ failed: 4, lockedOut: 1 });
    // Another address is not affected.
    expect((await t.login('10.0.0.7', 'alice', 'right')).ok).toBe(true);
    // The lockout ends.
    vi.advanceTimersByTime(301_000);
    expect((await t.login('10.0.0.9', 'alice', 'right')).ok).toBe(true);
  });

  test('spraying many user names from one address locks the address out', async () => {
    const { users } = countedUsers();
    const t = new LoginThrottle(users, OPTS);
    for (let i = 0; i < 6; i++) await t.login('10.0.0.9', `user${i}`, 'x');
    expect((await t.login('10.0.0.9', 'alice', 'right')).ok).toBe(false);
  });

  test('failures spread wider than the window never lock anyone out', async () => {
    const { users } = countedUsers();
    const t = new LoginThrottle(users, OPTS);
    for (let i = 0; i < 10; i++) {
      await t.login('10.0.0.9', 'alice', 'wrong');
      vi.advanceTimersByTime(31_000);
    }
    expect((await t.login('10.0.0.9', 'alice', 'right')).ok).toBe(true);
  });
});
