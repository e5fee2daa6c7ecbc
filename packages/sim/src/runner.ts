/**
 * Runs the simulated controller over any byte transport: control bytes in (`receive`), status
 * payloads out (`SimTransport.send`). Owns the state and health loops, the link faults (drop,
 * latency), the reply batching (the replies to one incoming chunk leave as one payload) and the
 * interlocks: the command rate limit, the payload bound, the emergency stop that overrides
 * everything queued, and the deadman (`operatorLeft`). The clock and the random source are
 * injected; no sockets here.
 */
import { ControlInput, isEmergencyStop, type Item } from '@armtwin/controller';
import type { Clock } from '@armtwin/protocol';
import { applyFault, NO_FAULTS, type Fault, type FaultState } from './faults.ts';
import { SimModel } from './model.ts';
import { DEFAULT_SIM_MODEL_OPTIONS } from './options.ts';
import {
  DEFAULT_SIM_RUNNER_OPTIONS,
  MAX_STATE_RATE,
  type SimRunnerOptions,
} from './runner-options.ts';
import { StatusWriter } from './status-writer.ts';
import { TickLoop } from './tick-loop.ts';

export type PayloadKind = 'state' | 'health' | 'reply';

export interface SimTransport {
  /**
   * Sends one status payload; the runner does not reuse the buffer. `samples`: the `$TIM`
   * samples in it (a state payload carries several when the loop caught up; others one).
   */
  send(payload: Buffer, kind: PayloadKind, samples: number): void;
}

export {
  DEFAULT_SIM_RUNNER_OPTIONS,
  MAX_STATE_RATE,
  type SimRunnerOptions,
} from './runner-options.ts';

/** The controller's replies, declared once in @armtwin/controller. */
export { DEADMAN_REPLY, OVERSIZE_REPLY, RATE_LIMIT_REPLY } from '@armtwin/controller';

export class SimRunner {
  readonly model: SimModel;
  readonly counters = {
    statePayloads: 0,
    stateSamples: 0,
    droppedSamples: 0,
    /** State samples never sent because the process stalled longer than maxCatchUpMs. */
    skippedSamples: 0,
    healthPayloads: 0,
    replyPayloads: 0,
    /** Reader errors by kind. */
    rejected: {} as Record<string, number>,
    discardedQueued: 0,
    /** Commands dropped by the rate limit. */
    rateLimited: 0,
    /** Control payloads refused for their size. */
    oversizePayloads: 0,
    /** Stops made because the operator's presence went to 0 while the arm was moving. */
    deadmanStops: 0,
  };
  /** The control input in front of the core: reader, payload bound, rate limit. */
  readonly input: ControlInput;
  faults: FaultState = { ...NO_FAULTS };
  private readonly o: SimRunnerOptions;
  private readonly writer = new StatusWriter();
  private readonly stateLoop: TickLoop;
  private readonly healthLoop: TickLoop;
  private lastStamp = -1;
  private readonly pending = new Set<unknown>(); // latency timers
  private inbound: { due: number; items: Item[]; timer: unknown }[] = [];

  constructor(
    private readonly transport: SimTransport,
    private readonly clock: Clock,
    options: Partial<SimRunnerOptions> = {},
  ) {
    const o = (this.o = { ...DEFAULT_SIM_RUNNER_OPTIONS, ...options });
    if (!(o.rate > 0 && o.rate <= MAX_STATE_RATE))
      throw new RangeError(`state rate must be in (0, ${MAX_STATE_RATE}] Hz`);
    if (!(o.healthRate > 0 && o.healthRate <= MAX_STATE_RATE))
      throw new RangeError('health rate must be > 0 Hz');
    this.model = new SimModel(o.model, clock.now());
    this.input = new ControlInput(this.model.core, o, clock.now());
    this.counters.rejected = this.input.counters.rejected;
    this.stateLoop = new TickLoop(clock, (t, n) => this.stateTicks(t, n), {
      hz: o.rate,
      maxBatch: Math.max(1, Math.ceil((o.rate * o.maxCatchUpMs) / 1000)),
    });
    this.healthLoop = new TickLoop(clock, (t, n) => this.healthTick(t[n - 1]!), {
      hz: o.healthRate,
      maxBatch: 1,
    });
    this.applyFaults(o.faults);
  }

  start(): void {
    this.stateLoop.startLoop();
    this.healthLoop.startLoop();
  }

  /** Stops the loops and drops whatever latency still holds back. */
  stop(): void {
    this.stateLoop.stopLoop();
    this.healthLoop.stopLoop();
    for (const t of this.pending) this.clock.clearTimeout(t);
    this.pending.clear();
    for (const q of this.inbound) this.clock.clearTimeout(q.timer);
    this.inbound = [];
  }

  /** Control bytes as they arrive (an MQTT payload, a serial chunk). */
  receive(chunk: string | Uint8Array): void {
    this.stateLoop.catchUp(); // samples due before this command go out as they were
    const taken = this.input.take(chunk, this.clock.now());
    this.counters.oversizePayloads = this.input.counters.oversizePayloads;
    this.counters.rateLimited = this.input.rateLimited;
    if ('refused' in taken) return this.reply([taken.refused]);
    const items = taken.items;
    if (items.length === 0) return;
    const latency = this.faults.latencyMs;
    const stopAt = items.findIndex((it) => ('frame' in it || 'group' in it) && isEmergencyStop(it));
    if (stopAt >= 0) {
      // The emergency stop acts on arrival and discards every command still queued.
      this.discardQueued();
      this.execute(items.slice(0, stopAt + 1));
      items.splice(0, stopAt + 1);
      if (items.length === 0) return;
    }
    if (latency <= 0) return this.execute(items);
    const entry = { due: this.clock.now() + latency, items, timer: undefined as unknown };
    entry.timer = this.clock.setTimeout(() => {
      this.inbound = this.inbound.filter((q) => q !== entry);
      this.stateLoop.catchUp();
      this.execute(entry.items);
    }, latency);
    this.inbound.push(entry);
  }

  /**
   * The deadman: the operator's presence went to `0` (it let go, or its last will). If a move
   * is under way or a command is still queued, every servo stops where it is, as `#255PDST!`
   * would, and the queue is discarded; answered `$ERR:deadman stop!`. At rest it does nothing.
   * Returns whether it stopped the arm.
   */
  operatorLeft(): boolean {
    this.stateLoop.catchUp();
    const t = this.clock.now();
    const out: string[] = [];
    this.model.advance(t);
    if (!this.model.core.operatorLeft(t, out, this.inbound.length > 0)) return false;
    this.discardQueued();
    this.counters.deadmanStops++;
    this.reply(out);
    return true;
  }

  /**
   * Puts the arm at a pose at once (`SimModel.placeAt`): what is under way stops and every
   * command still queued (a latency fault) is dropped. Returns the pulses placed by servo id;
   * throws, changing nothing, for a servo the arm lacks or a pulse that is not a number.
   */
  placeAt(pulses: ReadonlyMap<number, number>): Map<number, number> {
    this.stateLoop.catchUp();
    const t = this.clock.now();
    const placed = this.model.placeAt(pulses, t);
    this.discardQueued();
    return placed;
  }

  /** Applies faults now; returns the faults in force. Throws for a servo the arm lacks. */
  applyFaults(faults: Fault[]): FaultState {
    const t = this.clock.now();
    const overheatC = this.o.model.overheatC ?? DEFAULT_SIM_MODEL_OPTIONS.overheatC;
    for (const f of faults) this.faults = applyFault(this.model, this.faults, f, t, overheatC);
    return this.faults;
  }

  private discardQueued(): void {
    for (const q of this.inbound) {
      this.clock.clearTimeout(q.timer);
      this.counters.discardedQueued += q.items.length;
    }
    this.inbound = [];
  }

  private execute(items: Item[]): void {
    const t = this.clock.now();
    this.model.advance(t);
    this.reply(this.input.run(items, t), t);
  }

  /** Sends replies as one payload, `$TIM` first. */
  private reply(replies: string[], t = this.clock.now()): void {
    if (replies.length === 0) return;
    const w = this.writer.reset();
    if (this.o.stamp) w.time(Math.round(t));
    for (const r of replies) w.text(r);
    this.counters.replyPayloads++;
    this.out(w.take(), 'reply');
  }

  private stateTicks(times: Float64Array, n: number): void {
    this.counters.skippedSamples = this.stateLoop.skipped;
    const w = this.writer.reset();
    const s = this.model.servos;
    const drop = this.faults.dropPercent;
    const before = this.counters.stateSamples;
    for (let j = 0; j < n; j++) {
      const t = times[j]!;
      this.model.advance(t);
      const stamp = Math.round(t);
      if (stamp <= this.lastStamp) continue; // never two samples with the same $TIM
      this.lastStamp = stamp;
      if (drop > 0 && this.o.random() * 100 < drop) {
        this.counters.droppedSamples++;
        continue;
      }
      if (this.o.stamp) w.time(stamp);
      w.groupStart();
      for (let i = 0; i < s.count; i++) {
        if (this.model.reportsAngle[i]) w.angle(s.ids[i]!, this.model.angleAt(i, t));
        else w.position(s.ids[i]!, this.model.reportedPwm(i, t));
      }
      w.groupEnd();
      this.counters.stateSamples++;
    }
    if (w.length === 0) return;
    this.counters.statePayloads++;
    this.out(w.take(), 'state', this.counters.stateSamples - before);
  }

  private healthTick(t: number): void {
    this.model.advance(t);
    const s = this.model.servos;
    const w = this.writer.reset();
    if (this.o.stamp) w.time(Math.round(t));
    w.groupStart();
    for (let i = 0; i < s.count; i++) w.health(s.ids[i]!, s.temp[i]!, s.takeMinMv(i));
    w.groupEnd();
    this.counters.healthPayloads++;
    this.out(w.take(), 'health');
  }

  private out(payload: Buffer, kind: PayloadKind, samples = 1): void {
    const latency = this.faults.latencyMs;
    if (latency <= 0) return this.transport.send(payload, kind, samples);
    const timer = this.clock.setTimeout(() => {
      this.pending.delete(timer);
      this.transport.send(payload, kind, samples);
    }, latency);
    this.pending.add(timer);
  }
}
