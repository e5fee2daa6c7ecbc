/**
 * A control payload on its way into the controller: the streaming reader, the payload bound, the
 * rate limit (./rate-limit.ts), reader errors counted by kind and answered (a few per payload),
 * then the core. A driver that queues commands (the sim's latency fault) takes the admitted
 * items with `take` and runs them later with `run`; one that does not calls `receive`.
 */
import {
  createReader,
  encodeControllerError,
  MAX_PAYLOAD_BYTES,
  type ReaderError,
} from '@armtwin/protocol';
import type { ControllerCore } from './core.ts';
import { CommandGate, type Input } from './rate-limit.ts';

export type Item = Input | { error: ReaderError } | { limited: true };

/** What runs admitted commands: the core (`ControllerCore`), or a gate in front of it. */
export type CommandRunner = Pick<ControllerCore, 'execute' | 'executeGroup'>;

export const RATE_LIMIT_REPLY = 'rate limit';
export const OVERSIZE_REPLY = 'payload too large';

export interface ControlInputOptions {
  /** Commands per second, sustained (a group is one command). */
  commandRate: number;
  /** Commands at once after a quiet spell. */
  commandBurst: number;
  /** Control payloads longer than this are refused whole, bytes. */
  maxPayloadBytes: number;
  /** `$ERR` replies per payload for bad input, at most. */
  maxErrorsPerChunk: number;
  /** Told the first time each kind of problem happens. */
  onFirst(kind: string, message: string): void;
}

export const DEFAULT_CONTROL_INPUT_OPTIONS: ControlInputOptions = {
  commandRate: 50,
  commandBurst: 100,
  maxPayloadBytes: MAX_PAYLOAD_BYTES,
  maxErrorsPerChunk: 8,
  onFirst: () => {},
};

export class ControlInput {
  readonly counters = {
    /** Reader errors by kind. */
    rejected: {} as Record<string, number>,
    oversizePayloads: 0,
  };
  private readonly items: (Input | { error: ReaderError })[] = [];
  private readonly reader;
  private readonly gate: CommandGate;
  private readonly o: ControlInputOptions;

  constructor(
    private readonly core: CommandRunner,
    options: Partial<ControlInputOptions>,
    now: number,
  ) {
    this.o = { ...DEFAULT_CONTROL_INPUT_OPTIONS, ...options };
    this.gate = new CommandGate(this.o.commandRate, this.o.commandBurst, now);
    this.reader = createReader({
      onFrame: (frame) => this.items.push({ frame }),
      onGroup: (group) => this.items.push({ group }),
      onError: (error) => this.items.push({ error }),
    });
  }

  /** Commands dropped by the rate limit. */
  get rateLimited(): number {
    return this.gate.dropped;
  }

  /**
   * Parses a payload and passes it through the payload bound and the rate limit: the items to
   * run, or the reply for a payload refused whole.
   */
  take(chunk: string | Uint8Array, now: number): { items: Item[] } | { refused: string } {
    if (chunk.length > this.o.maxPayloadBytes) {
      if (this.counters.oversizePayloads++ === 0)
        this.o.onFirst('control:oversize', `control payload of ${chunk.length} bytes refused`);
      return { refused: encodeControllerError(OVERSIZE_REPLY) };
    }
    this.reader.feed(chunk);
    const out: Item[] = [];
    for (const it of this.items.splice(0)) {
      if ('error' in it) {
        out.push(it);
        continue;
      }
      const verdict = this.gate.admit(it, now);
      if (verdict === 'pass') out.push(it);
      else if (verdict === 'refuse') {
        if (this.gate.dropped === 1)
          this.o.onFirst('control:rate-limit', `commands over ${this.o.commandRate}/s dropped`);
        out.push({ limited: true });
      }
    }
    return { items: out };
  }

  /** Runs admitted items at t; returns the replies. */
  run(items: readonly Item[], t: number): string[] {
    const replies: string[] = [];
    let errors = 0;
    for (const it of items) {
      if ('frame' in it) this.core.execute(it.frame, t, replies);
      else if ('group' in it) this.core.executeGroup(it.group, t, replies);
      else if ('limited' in it) replies.push(encodeControllerError(RATE_LIMIT_REPLY));
      else {
        const kind = it.error.kind;
        this.counters.rejected[kind] = (this.counters.rejected[kind] ?? 0) + 1;
        if (this.counters.rejected[kind] === 1)
          this.o.onFirst(`control:${kind}`, `${it.error.message}: ${it.error.text}`);
        if (errors++ < this.o.maxErrorsPerChunk)
          replies.push(encodeControllerError(`${kind} ${it.error.text}`));
      }
    }
    return replies;
  }

  /** `take` then `run` at t. */
  receive(chunk: string | Uint8Array, t: number): string[] {
    const r = this.take(chunk, t);
    return 'refused' in r ? [r.refused] : this.run(r.items, t);
  }
}
