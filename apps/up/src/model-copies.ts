/**
 * The model copies of the arms `armtwin up` knows (docs/protocol.md § Modes): arm `{id}`'s
 * copy is a full simulated arm `{id}-model`, started on demand on the same broker, with the
 * arm's profile read from its profile file now and its keep-out zones followed from that file
 * (zones-follow.ts, as the arm's own sim does), its own control arbiter and deadman. `start`
 * puts a new or running copy at a pose (`SimRunner.placeAt`); a copy stops on `stop`, on
 * `stopAll` (when `armtwin up` stops) and by itself after `idleMs` with nothing received on its
 * topics and no `start` (./model-idle.ts).
 */
import type { IClientOptions, MqttClient } from 'mqtt';
import {
  linkOptions,
  MAX_REAL_ARM_ID_LENGTH,
  MODEL_ARM_SUFFIX,
  isModelArmId,
  modelArmId,
  SYSTEM_CLOCK,
  type Clock,
} from '@armtwin/protocol';
import { followZones, loadSimProfile, simWill, startMqttSim, type MqttSim } from '@armtwin/sim';
import { IdleWatch } from './model-idle.ts';

export interface ModelCopiesOptions {
  /** A copy stops after this long with nothing received on its topics and no `start`, ms. */
  idleMs: number;
  /** The copies' state rate, Hz (`armtwin up` gives its arms' rate). */
  rate: number;
}

export const DEFAULT_MODEL_COPIES_OPTIONS: ModelCopiesOptions = {
  idleMs: 10 * 60_000,
  rate: 50,
};

/** Where an arm's profile is: its name (folder) and the models folder holding it. */
export interface ModelArmSource {
  profile: string;
  modelsDir: string;
}

export interface ModelCopiesDeps {
  /**
   * Where arm `armId`'s profile is, or undefined for an arm not known here (`armtwin up`: an arm
   * it simulates, else one whose announced profile is in its models folders).
   */
  source(armId: string): ModelArmSource | undefined;
  /** Connects a copy's MQTT client (in `armtwin up`: in-process, as the copy's device). */
  connect(copyId: string, options: IClientOptions): MqttClient;
  /** Told once per kind of problem. */
  onFirst(kind: string, message: string): void;
  /** Progress lines for the operator. */
  say(message: string): void;
  clock?: Clock;
}

export interface StartedCopy {
  /** Whether this call started it (false: it was running and was put at the pose). */
  started: boolean;
  /** The pulses put, by servo id (each held within its servo's limits). */
  pulses: Map<number, number>;
}

interface Copy {
  sim: MqttSim;
  zones: { stop(): void };
  idle: IdleWatch;
}

export class ModelCopies {
  private readonly o: ModelCopiesOptions;
  private readonly clock: Clock;
  private readonly copies = new Map<string, Copy>();
  /** Copies being stopped: a new one waits, so the old one's `online 0` cannot follow its `1`. */
  private readonly stopping = new Map<string, Promise<void>>();

  constructor(
    private readonly deps: ModelCopiesDeps,
    options: Partial<ModelCopiesOptions> = {},
  ) {
    this.o = { ...DEFAULT_MODEL_COPIES_OPTIONS, ...options };
    this.clock = deps.clock ?? SYSTEM_CLOCK;
  }

  /** Why arm `armId` cannot have a copy here, or '' when it can. */
  refusal(armId: string): string {
    if (isModelArmId(armId)) return `"${armId}" is a model copy; a copy has no copy`;
    if (!this.deps.source(armId))
      return `no arm "${armId}" to copy: not simulated here, and no profile of its own announced on arm/${armId}/profile is in the models folders`;
    if (armId.length > MAX_REAL_ARM_ID_LENGTH)
      return `arm "${armId}" has no model copy: ${armId}${MODEL_ARM_SUFFIX} would be over 32 characters`;
    return '';
  }

  /** The ids of arm `armId`'s servos (its profile as the file is now). */
  servoIds(armId: string): number[] {
    const copy = this.copies.get(armId);
    if (copy) return Array.from(copy.sim.runner.model.servos.ids);
    const src = this.source(armId);
    return loadSimProfile(src.profile, src.modelsDir).model.arm!.servos.map((s) => s.id);
  }

  running(armId: string): boolean {
    return this.copies.has(armId);
  }

  /**
   * Starts arm `armId`'s copy if it is not running, and puts it at `pulses` (servo id → µs; the
   * ids must be its servos'). Throws for an arm that cannot have a copy or a profile that does
   * not load.
   */
  async start(armId: string, pulses: ReadonlyMap<number, number>): Promise<StartedCopy> {
    await this.stopping.get(armId);
    const running = this.copies.get(armId);
    if (running) {
      running.idle.touch();
      return { started: false, pulses: running.sim.runner.placeAt(pulses) };
    }
    const copy = this.launch(armId);
    return { started: true, pulses: copy.sim.runner.placeAt(pulses) };
  }

  /** Stops arm `armId`'s copy (its `online` goes `0`); nothing when it is not running. */
  async stop(armId: string, why = 'stopped'): Promise<void> {
    const copy = this.copies.get(armId);
    if (!copy) return this.stopping.get(armId);
    this.copies.delete(armId);
    copy.idle.stop();
    copy.zones.stop();
    const done = copy.sim.stop().finally(() => this.stopping.delete(armId));
    this.stopping.set(armId, done);
    await done;
    this.deps.say(`model copy "${modelArmId(armId)}": ${why}`);
  }

  /** Stops every copy (`armtwin up` stopping). */
  async stopAll(): Promise<void> {
    await Promise.all([...this.copies.keys()].map((id) => this.stop(id)));
  }

  private source(armId: string): ModelArmSource {
    const why = this.refusal(armId);
    if (why) throw new RangeError(why);
    return this.deps.source(armId)!;
  }

  /** Starts the copy's sim on its own client (synchronously: two starts cannot race). */
  private launch(armId: string): Copy {
    const src = this.source(armId);
    const profile = loadSimProfile(src.profile, src.modelsDir); // a bad file throws here
    const copyId = modelArmId(armId);
    const client = this.deps.connect(copyId, {
      clientId: `armtwin-sim-${copyId}`,
      will: simWill(copyId),
      ...linkOptions(),
      queueQoSZero: false,
    });
    const sim = startMqttSim(client, {
      armId: copyId,
      rate: this.o.rate,
      onFirst: this.deps.onFirst,
      model: profile.model,
      profile,
      clock: this.clock,
    });
    // The arm's zones: the same profile file, followed as the arm's own sim follows it.
    const zones = followZones({
      client,
      armId: copyId,
      name: src.profile,
      modelsDir: src.modelsDir,
      sim: profile,
      runner: sim.runner,
      onFirst: this.deps.onFirst,
    });
    const idle = new IdleWatch(this.clock, this.o.idleMs, () => {
      const minutes = Math.round(this.o.idleMs / 6000) / 10;
      void this.stop(armId, `stopped, idle for ${minutes} min`);
    });
    client.on('message', () => idle.touch());
    const copy: Copy = { sim, zones, idle };
    this.copies.set(armId, copy);
    this.deps.say(`model copy "${copyId}" of "${armId}" started (profile ${src.profile})`);
    return copy;
  }
}
