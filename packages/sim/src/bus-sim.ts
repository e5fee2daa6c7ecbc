/**
 * `armtwin sim --bus dynamixel|feetech --serial PATH`: the simulated arm as a servo bus. One
 * emulated servo (`@armtwin/servo-bus`) per profile servo, with the profile's ids, starting at
 * the home pose (servo angle s at tick 2048 + polarity·s·4096/360, as the gateway reads it) and moving toward the goals the host
 * writes at the speeds it writes, as time passes. Temperature and voltage are the sim's ambient
 * temperature and supply (Dynamixel: the model's 12 V), and the faults show on the bus: a
 * stalled servo's shaft stays where it jammed and warms, an overheated one reads its
 * temperature (and drops torque past its limit, as the servo would), undervolt sets every
 * servo's input voltage. `BusSimCore` is pure (the clock is the caller's); `startBusSim` puts a
 * serial port around it.
 */
import { SerialPort } from 'serialport';
import type { Profile } from '@armtwin/robot';
import { SYSTEM_CLOCK, type Clock } from '@armtwin/protocol';
import {
  createEmulatedBus,
  degreesToTicks,
  withBenchFaults,
  type BenchFault,
  type BusProtocol,
  type EmulatedBus,
} from '@armtwin/servo-bus';
import type { Fault } from './faults.ts';
import type { HandMove } from './hand.ts';
import { DEFAULT_SIM_MODEL_OPTIONS } from './options.ts';

export interface BusSimOptions {
  protocol: BusProtocol;
  profile: Profile;
  /** Faults in force from the start (drop and latency do not apply on a bus). */
  faults: Fault[];
  /** Temperature a servo reads at rest, °C. */
  ambientC: number;
  /** Temperature a stalled servo warms to, °C, and one overheated without a figure. */
  stallC: number;
  overheatC: number;
  /** How often the emulated shafts are moved and the sensors set, ms. */
  tickMs: number;
  /** Faults of the bench: servos absent, extra or sharing an id, a field set (bench-faults.ts). */
  benchFaults: BenchFault[];
}

export const DEFAULT_BUS_SIM_OPTIONS = {
  faults: [],
  ambientC: DEFAULT_SIM_MODEL_OPTIONS.ambientC,
  stallC: 65,
  overheatC: DEFAULT_SIM_MODEL_OPTIONS.overheatC,
  tickMs: 20,
  benchFaults: [],
} satisfies Partial<BusSimOptions>;

export class BusSimCore {
  readonly bus: EmulatedBus;
  private readonly o: BusSimOptions;
  /** Where each stalled servo jammed, ticks. */
  private readonly stalled = new Map<number, number>();
  private readonly overheat = new Map<number, number>();
  private undervoltMv = 0;

  constructor(
    options: Partial<BusSimOptions> & Pick<BusSimOptions, 'protocol' | 'profile'>,
    startMs: number,
  ) {
    this.o = { ...DEFAULT_BUS_SIM_OPTIONS, ...options };
    const home = this.o.profile.poses.home ?? [];
    const bench = withBenchFaults(
      this.o.profile.servos.map((s, i) => ({
        id: s.id,
        position: degreesToTicks(Number.isFinite(home[i]) ? home[i]! : 0, {
          id: s.id,
          direction: s.polarity,
        }),
        temperatureC: this.o.ambientC,
      })),
      this.o.benchFaults,
    );
    this.bus = createEmulatedBus({ protocol: this.o.protocol, startMs, ...bench });
    for (const f of this.o.faults) this.apply(f);
    this.sense();
  }

  /** A fault of `armtwin sim`'s set; drop and latency are link faults and do nothing here. */
  apply(f: Fault): void {
    switch (f.fault) {
      case 'stall': {
        const s = this.bus.servo(f.id);
        if (s) this.stalled.set(f.id, s.position);
        break;
      }
      case 'overheat':
        this.overheat.set(f.id, f.celsius ?? this.o.overheatC);
        break;
      case 'undervolt':
        this.undervoltMv = f.mv;
        break;
      case 'clear':
        if (f.id === undefined) {
          this.stalled.clear();
          this.overheat.clear();
          this.undervoltMv = 0;
        } else {
          this.stalled.delete(f.id);
          this.overheat.delete(f.id);
        }
        break;
      case 'drop':
      case 'latency':
        break;
      default: {
        const never: never = f;
        throw new Error(`unhandled fault ${String(never)}`);
      }
    }
    this.sense();
  }

  /** Bytes from the host; the servos' answers. Time is brought up to `nowMs` first. */
  feed(bytes: Uint8Array, nowMs: number): Uint8Array {
    this.advance(nowMs);
    return this.bus.feed(bytes);
  }

  /**
   * A hand puts servo `id`'s shaft at `degrees` (servo angle, the profile's polarity) at
   * `nowMs`; false when the bus has no such servo.
   */
  hand(move: HandMove, nowMs: number): boolean {
    this.advance(nowMs);
    const s = this.bus.servo(move.id);
    const servo = this.o.profile.servos.find((p) => p.id === move.id);
    if (!s) return false;
    s.setPosition(degreesToTicks(move.degrees, { id: move.id, direction: servo?.polarity ?? 1 }));
    return true;
  }

  /** Moves the shafts to `nowMs`; a stalled shaft stays where it jammed. */
  advance(nowMs: number): void {
    this.bus.advance(nowMs);
    for (const [id, ticks] of this.stalled) this.bus.servo(id)?.setPosition(ticks);
  }

  /** Sets what the sensors read from the faults in force. */
  private sense(): void {
    for (const s of this.bus.servos) {
      const hot = this.overheat.get(s.id) ?? (this.stalled.has(s.id) ? this.o.stallC : undefined);
      s.setTemperature(hot ?? this.o.ambientC);
      if (this.undervoltMv > 0) s.setVoltage(this.undervoltMv / 1000);
    }
  }
}

export interface BusSim {
  core: BusSimCore;
  /** Resolves when the line closes under the sim. */
  closed: Promise<string>;
  stop(): Promise<void>;
}

export async function startBusSim(
  options: Partial<BusSimOptions> &
    Pick<BusSimOptions, 'protocol' | 'profile'> & {
      path: string;
      baudRate: number;
      clock?: Clock;
      onFirst?: (kind: string, message: string) => void;
    },
): Promise<BusSim> {
  const clock = options.clock ?? SYSTEM_CLOCK;
  const core = new BusSimCore(options, clock.now());
  const port = new SerialPort({ path: options.path, baudRate: options.baudRate, autoOpen: false });
  await new Promise<void>((resolve, reject) => port.open((err) => (err ? reject(err) : resolve())));
  port.on('data', (chunk: Buffer) => {
    const reply = core.feed(chunk, clock.now());
    if (reply.length) port.write(Buffer.from(reply));
  });
  port.on('error', (err) => options.onFirst?.('serial', err.message));
  let timer: unknown;
  const tick = () => {
    core.advance(clock.now());
    timer = clock.setTimeout(tick, options.tickMs ?? DEFAULT_BUS_SIM_OPTIONS.tickMs);
  };
  tick();
  const closed = new Promise<string>((resolve) =>
    port.on('close', (err: Error | null) => {
      clock.clearTimeout(timer);
      resolve(err?.message ?? 'closed');
    }),
  );
  return {
    core,
    closed,
    async stop() {
      clock.clearTimeout(timer);
      if (port.isOpen) await new Promise<void>((resolve) => port.close(() => resolve()));
    },
  };
}
