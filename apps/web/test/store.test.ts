import { describe, expect, it } from 'vitest';
import { angleFromPwm, encodeGroup, encodeHealth, encodePosition } from '@armtwin/protocol';
import { DEMO_ARM } from '@armtwin/ik';
import { ArmStore } from '../src/core/store/ArmStore.ts';
import { RingBuffer } from '../src/core/store/RingBuffer.ts';
import { RateMeter } from '../src/core/store/RateMeter.ts';
import { PingTracker } from '../src/core/store/PingTracker.ts';

const state = (pwms: number[]) => encodeGroup(pwms.map((p, i) => encodePosition(i, p)));

describe('RingBuffer', () => {
  it('keeps the newest `capacity` values, oldest first', () => {
    const r = new RingBuffer(3);
    expect(r.latest()).toBeNaN();
    for (const v of [1, 2, 3, 4, 5]) r.push(v);
    expect(r.length).toBe(3);
    expect([r.at(0), r.at(1), r.at(2)]).toEqual([3, 4, 5]);
    const out = new Float64Array(3);
    expect(r.copyInto(out)).toBe(3);
    expect(Array.from(out)).toEqual([3, 4, 5]);
    expect(r.latest()).toBe(5);
  });
  it('copies only the newest values into a shorter array', () => {
    const r = new RingBuffer(5);
    for (const v of [1, 2, 3, 4]) r.push(v);
    const out = [0, 0];
    r.copyInto(out);
    expect(out).toEqual([3, 4]);
  });
});

describe('RateMeter', () => {
  it('counts events per second over the last second', () => {
    const m = new RateMeter();
    for (let t = 0; t < 2000; t += 20) m.add(t);
    expect(m.rate(2000)).toBeCloseTo(50, -1);
    expect(m.rate(5000)).toBe(0);
  });
});

describe('PingTracker', () => {
  it('turns an echo into a round trip and ignores unknown sequence numbers', () => {
    const p = new PingTracker(7);
    const seq = p.send(1000);
    expect(seq).toBe(7);
    p.echo(99, 1010);
    expect(p.rttMs).toBeNaN();
    p.echo(seq, 1012.5);
    expect(p.rttMs).toBe(12.5);
    p.echo(seq, 2000); // a duplicate echo counts once
    expect(p.rttMs).toBe(12.5);
  });
});

describe('ArmStore', () => {
  it('takes positions from a state group and interpolates between reports', () => {
    const s = new ArmStore({ twinMode: 'interpolate' });
    s.ingest(`$TIM:1700000000000!${state([1500, 1500, 1500, 1500, 1500, 1500])}`, 0);
    s.ingest(state([1500 + 741, 1500, 1500, 1500, 1500, 1500]), 200); // +100.04° on servo 000
    expect(s.pwm[0]).toBe(2241);
    s.sample(200);
    expect(s.rendered[0]).toBeCloseTo(0, 6);
    s.sample(200 + s.expectedStateIntervalMs / 2);
    expect(s.rendered[0]).toBeCloseTo(50.02, 1);
    s.sample(10_000);
    expect(s.rendered[0]).toBeCloseTo(100.04, 1);
    expect(s.counters.frames).toBe(13); // $TIM + 12 positions
  });

  it('draws each report as it is once reports come faster than 100/s (no tween lag)', () => {
    const s = new ArmStore({ twinMode: 'interpolate' });
    // 250 Hz for a second, then a burst taken in at one instant (a busy page).
    for (let k = 0; k <= 250; k++)
      s.ingest(
        `$TIM:${1_700_000_000_000 + k * 4}!${state([1500, 1500, 1500, 1500, 1500, 1500])}`,
        k * 4,
      );
    s.ingest(state([1600, 1500, 1500, 1500, 1500, 1500]), 1004);
    s.ingest(state([1700, 1500, 1500, 1500, 1500, 1500]), 1004);
    s.sample(1004);
    expect(s.pwm[0]).toBe(1700);
    expect(s.rendered[0]).toBe(angleFromPwm(1700, DEMO_ARM.servos[0]!.polarity));
    expect(s.lastStateStamp).toBe(1_700_000_001_000);
  });

  it('handles payloads split anywhere and several frames per payload', () => {
    const s = new ArmStore();
    const text =
      state([1000, 1100, 1200, 1300, 1400, 1500]) + state([1001, 1101, 1201, 1301, 1401, 1501]);
    for (let i = 0; i < text.length; i += 7) s.ingest(text.slice(i, i + 7), i);
    expect(Array.from(s.pwm)).toEqual([1001, 1101, 1201, 1301, 1401, 1501]);
    expect(s.counters.dropped).toBe(0);
  });

  it('counts dropped input by kind, and keeps the good frames', () => {
    const s = new ArmStore();
    s.ingest('noise#000P15#001P1600!#002P9999!', 0);
    expect(s.pwm[1]).toBe(1600);
    expect(s.counters.dropped).toBe(3);
    expect(s.counters.droppedByKind.junk).toBe(1);
    expect(s.counters.droppedByKind.truncated).toBe(1);
    expect(s.counters.droppedByKind['out-of-range']).toBe(1);
  });

  it('records health rows in the ring buffers, stamped by $TIM', () => {
    const s = new ArmStore({ historyLength: 4 });
    for (let k = 0; k < 6; k++) {
      const group = encodeGroup([0, 1, 2, 3, 4, 5].map((i) => encodeHealth(i, 30 + k, 7400 - i)));
      s.ingest(`$TIM:${1_700_000_000_000 + k * 500}!${group}`, k * 500);
    }
    expect(s.temp[0]).toBe(35);
    expect(s.mv[5]).toBe(7395);
    expect(s.history.time.length).toBe(4);
    expect(s.history.time.latest()).toBe(1_700_000_002.5);
    expect(s.history.temp[2]!.at(0)).toBe(32);
    expect(s.history.volt[5]!.latest()).toBeCloseTo(7.395, 6);
  });

  it('is stale with no state for more than 1 s, fresh again on the next report', () => {
    const s = new ArmStore();
    expect(s.isStale(0)).toBe(true);
    s.ingest(state([1500, 1500, 1500, 1500, 1500, 1500]), 1000);
    expect(s.isStale(1500)).toBe(false);
    expect(s.isStale(2000)).toBe(false);
    expect(s.isStale(2001)).toBe(true);
    s.ingest(encodeHealth(0, 30, 7400), 2500); // health alone does not make the state fresh
    expect(s.isStale(2600)).toBe(true);
    s.ingest(state([1500, 1500, 1500, 1500, 1500, 1500]), 3000);
    expect(s.isStale(3000)).toBe(false);
  });

  it('keeps the $KMS reply and matches ping echoes', () => {
    const s = new ArmStore();
    s.ingest('$KMS:2!', 0);
    expect([s.kmsReply, s.kmsReplies]).toEqual([2, 1]);
    const seq = s.ping.send(100);
    s.ingest(`$PNG:${seq}!`, 104);
    expect(s.ping.rttMs).toBe(4);
  });

  it('forgets the arm on resetArm', () => {
    const s = new ArmStore();
    s.ingest(state([1600, 1500, 1500, 1500, 1500, 1500]), 0);
    s.armOnline = true;
    s.resetArm();
    expect(s.pwm[0]).toBeNaN();
    expect(s.armOnline).toBeNull();
    expect(s.isStale(1)).toBe(true);
  });
});
