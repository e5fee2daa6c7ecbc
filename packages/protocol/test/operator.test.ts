import { afterEach, beforeEach, describe, expect, it, vi } from 'vitest';
import {
  OPERATOR_BEAT_MS,
  OPERATOR_LEASE_MS,
  OperatorWatch,
  parseOperator,
  type LetGoReason,
} from '../src/index.ts';

const timers = {
  setTimeout: (fn: () => void, ms: number) => setTimeout(fn, ms),
  clearTimeout: (h: unknown) => clearTimeout(h as ReturnType<typeof setTimeout>),
};

function watch(leaseMs?: number) {
  const letGo: LetGoReason[] = [];
  const w = new OperatorWatch(timers, (r) => letGo.push(r), leaseMs);
  return { w, letGo };
}

beforeEach(() => vi.useFakeTimers());
afterEach(() => vi.useRealTimers());

describe('operator topic payloads', () => {
  it('1 holds, 0 releases, anything else is not a signal', () => {
    expect(parseOperator('1')).toBe('hold');
    expect(parseOperator(new TextEncoder().encode(' 0\n'))).toBe('release');
    for (const bad of ['', '2', 'true', '10', '<b>1</b>']) expect(parseOperator(bad)).toBeNull();
  });

  it('the lease outlasts several beats and stays under 1.5 × the HUD’s 2 s keep-alive', () => {
    expect(OPERATOR_LEASE_MS).toBeGreaterThanOrEqual(4 * OPERATOR_BEAT_MS);
    expect(OPERATOR_LEASE_MS).toBeLessThan(1.5 * 2000);
  });
});

describe('OperatorWatch', () => {
  it('a 0 lets go at once, whatever came before', () => {
    const { w, letGo } = watch();
    w.receive('0');
    w.receive('1');
    w.receive('0');
    expect(letGo).toEqual(['released', 'released']);
    expect(w.state).toBe('none');
  });

  it('a single 1 (a script, mosquitto_pub -r) is never timed out', () => {
    const { w, letGo } = watch();
    w.receive('1');
    vi.advanceTimersByTime(60_000);
    expect(letGo).toEqual([]);
    expect(w.state).toBe('held');
  });

  it('a beating operator is held as long as it beats, and let go one lease after it stops', () => {
    const { w, letGo } = watch();
    for (let i = 0; i < 40; i++) {
      w.receive('1');
      vi.advanceTimersByTime(OPERATOR_BEAT_MS);
    }
    expect(letGo).toEqual([]);
    expect(w.state).toBe('beating');
    vi.advanceTimersByTime(OPERATOR_LEASE_MS - OPERATOR_BEAT_MS - 1);
    expect(letGo).toEqual([]);
    vi.advanceTimersByTime(1);
    expect(letGo).toEqual(['lapsed']);
    expect(w.state).toBe('none');
    expect(w.counters).toMatchObject({ lapses: 1, releases: 0 });
    vi.advanceTimersByTime(60_000);
    expect(letGo).toEqual(['lapsed']); // once
  });

  it('a 0 from a beating operator cancels the lease: one let-go, not two', () => {
    const { w, letGo } = watch();
    w.receive('1');
    w.receive('1');
    w.receive('0');
    vi.advanceTimersByTime(60_000);
    expect(letGo).toEqual(['released']);
  });

  it('junk is counted and changes nothing; lease 0 turns the timeout off', () => {
    const { w, letGo } = watch(0);
    w.receive('1');
    w.receive('1');
    w.receive('yes');
    vi.advanceTimersByTime(60_000);
    expect(letGo).toEqual([]);
    expect(w.counters.ignored).toBe(1);
  });

  it('reset forgets the operator without acting', () => {
    const { w, letGo } = watch();
    w.receive('1');
    w.receive('1');
    w.reset();
    vi.advanceTimersByTime(60_000);
    expect(letGo).toEqual([]);
    expect(w.state).toBe('none');
  });
});
