import { describe, expect, it } from 'vitest';
import { CameraFeed, Fanout, FrameQueue, decodeH264Message, type FrameSink } from '../src/index.ts';

const drain = <T>(q: FrameQueue<T>) => {
  const out: T[] = [];
  for (let f = q.shift(); f !== undefined; f = q.shift()) out.push(f);
  return out;
};

describe('FrameQueue, latest (MJPEG)', () => {
  it('full: drops the oldest frame and counts it', () => {
    const q = new FrameQueue<number>({ capacity: 2, policy: 'latest' });
    for (let i = 1; i <= 5; i++) q.push(i, true);
    expect(q.dropped).toBe(3);
    expect(drain(q)).toEqual([4, 5]);
  });

  it('a replayed frame does not count against the capacity', () => {
    const q = new FrameQueue<number>({ capacity: 1, policy: 'latest' });
    q.push(0, true, true);
    q.push(1, true);
    q.push(2, true);
    expect(drain(q)).toEqual([0, 2]);
    expect(q.dropped).toBe(1);
  });
});

describe('FrameQueue, until-key (H.264)', () => {
  it('a new queue waits for a key frame', () => {
    const q = new FrameQueue<string>({ capacity: 4, policy: 'until-key' });
    q.push('p1', false);
    q.push('k', true);
    q.push('p2', false);
    expect(drain(q)).toEqual(['k', 'p2']);
    expect(q.dropped).toBe(1);
  });

  it('full: drops everything queued and every frame up to the next key frame', () => {
    const q = new FrameQueue<string>({ capacity: 2, policy: 'until-key' });
    q.push('k1', true);
    q.push('p1', false);
    q.push('p2', false); // over: k1 and p1 go, p2 too (it needs p1)
    expect(q.skipping).toBe(true);
    q.push('p3', false);
    q.push('k2', true);
    q.push('p4', false);
    expect(drain(q)).toEqual(['k2', 'p4']);
    expect(q.dropped).toBe(4);
  });

  it('a key frame supersedes frames still queued before it', () => {
    const q = new FrameQueue<string>({ capacity: 8, policy: 'until-key' });
    q.push('k1', true);
    q.push('p1', false);
    q.push('k2', true);
    expect(drain(q)).toEqual(['k2']);
    expect(q.dropped).toBe(2);
  });

  it('restart(): queued frames are stale and it waits for a key frame again', () => {
    const q = new FrameQueue<string>({ capacity: 8, policy: 'until-key' });
    q.push('k1', true);
    q.push('p1', false);
    q.restart();
    q.push('p2', false);
    expect(drain(q)).toEqual([]);
    expect(q.dropped).toBe(3);
  });
});

/** A viewer whose writes complete only when the test says so: a slow network. */
class SlowSink implements FrameSink {
  written: Uint8Array[] = [];
  private pending: (() => void)[] = [];
  write(data: Uint8Array, done: (err?: Error | null) => void) {
    this.written.push(data);
    this.pending.push(() => done());
  }
  complete(n = Infinity) {
    while (n-- > 0 && this.pending.length) this.pending.shift()!();
  }
}

describe('Fanout', () => {
  it('a slow viewer gets the newest frames, its backlog dropped and counted; a fast one gets all', () => {
    const f = new Fanout({ policy: 'latest', capacity: 2, maxViewers: 4 });
    const slow = new SlowSink();
    const fast: number[] = [];
    f.add(slow, 'slow', 0);
    f.add({ write: (d, done) => (fast.push(d[0]!), done()) }, 'fast', 0);
    for (let i = 0; i < 10; i++) f.publish(Uint8Array.of(i), true);
    expect(fast).toEqual([0, 1, 2, 3, 4, 5, 6, 7, 8, 9]);
    // one write in flight (frame 0), two queued (8, 9): 7 dropped
    slow.complete();
    slow.complete();
    slow.complete();
    expect(slow.written.map((d) => d[0])).toEqual([0, 8, 9]);
    const stats = f.stats();
    expect(stats.viewers.find((v) => v.remote === 'slow')).toMatchObject({
      sent: 3,
      dropped: 7,
      queued: 0,
    });
    expect(stats).toMatchObject({ framesIn: 10, framesSent: 13, dropped: 7 });
  });

  it('refuses viewers over maxViewers; a failed write removes the viewer', () => {
    const f = new Fanout({ policy: 'latest', capacity: 2, maxViewers: 1 });
    const v = f.add({ write: (_d, done) => done(new Error('EPIPE')) }, 'a', 0);
    expect(v).not.toBeNull();
    expect(f.add({ write: (_d, done) => done() }, 'b', 0)).toBeNull();
    f.publish(Uint8Array.of(1), true);
    expect(f.viewerCount).toBe(0);
    expect(f.stats().writeErrors).toBe(1);
  });
});

describe('CameraFeed', () => {
  const au = (n: number) => Uint8Array.of(0, 0, 0, 1, n);

  it('a new H.264 viewer gets the current group of pictures first, flagged replay, then live', () => {
    const feed = new CameraFeed();
    feed.accessUnit(au(1), false, 1); // before any key frame: not replayable
    feed.accessUnit(au(0x65), true, 2);
    feed.accessUnit(au(0x41), false, 3);
    const got: ReturnType<typeof decodeH264Message>[] = [];
    feed.watchH264({ write: (d, done) => (got.push(decodeH264Message(d)), done()) }, 'x', 0);
    feed.accessUnit(au(0x41), false, 4);
    const msgs = got.map((g) => (g.ok ? g.message : null));
    expect(msgs.map((m) => [m?.key, m?.replay, m?.timestampMs, m?.seq])).toEqual([
      [true, true, 2, 1],
      [false, true, 3, 2],
      [false, false, 4, 3],
    ]);
  });

  it("after an encoder restart a viewer skips to the new stream's key frame", () => {
    const feed = new CameraFeed();
    const slow = new SlowSink();
    feed.accessUnit(au(0x65), true, 1);
    feed.watchH264(slow, 'x', 0);
    feed.accessUnit(au(0x41), false, 2);
    feed.encoderRestarted();
    feed.accessUnit(au(0x41), false, 3);
    feed.accessUnit(au(0x65), true, 4);
    slow.complete();
    slow.complete();
    const seen = slow.written.map((d) => {
      const m = decodeH264Message(d);
      return m.ok ? m.message.timestampMs : -1;
    });
    expect(seen).toEqual([1, 4]);
  });

  it('a new MJPEG viewer gets the latest picture at once', () => {
    const feed = new CameraFeed();
    feed.jpeg(Uint8Array.of(0xff, 0xd8, 1, 0xff, 0xd9), 10);
    feed.jpeg(Uint8Array.of(0xff, 0xd8, 2, 0xff, 0xd9), 20);
    const parts: string[] = [];
    feed.watchMjpeg(
      { write: (d, done) => (parts.push(new TextDecoder('latin1').decode(d)), done()) },
      'x',
      0,
    );
    expect(parts).toHaveLength(1);
    expect(parts[0]).toContain('X-Timestamp: 20\r\n');
    expect(parts[0]).toContain('Content-Length: 5\r\n');
  });
});
