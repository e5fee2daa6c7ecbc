/** The simulated controller's runner (./runner.ts): its settings and their defaults, declared once. */
import { DEFAULT_CONTROL_INPUT_OPTIONS as INPUT } from '@armtwin/controller';
import type { Fault } from './faults.ts';
import type { SimModelOptions } from './options.ts';

export interface SimRunnerOptions {
  /** State rate, Hz (1–1000). */
  rate: number;
  /** Health rate, Hz. */
  healthRate: number;
  /** Put `$TIM:…!` first in every payload (MQTT: yes; a serial line, like real firmware: no). */
  stamp: boolean;
  /**
   * How far behind (ms) the state loop may fall and still send every sample it owes, batched
   * into one payload (each with its own `$TIM`); beyond that it skips ahead and counts.
   */
  maxCatchUpMs: number;
  /** Most `$ERR` replies to one incoming chunk; the rest are only counted. */
  maxErrorsPerChunk: number;
  /** Random numbers in [0, 1), for the drop fault. */
  random: () => number;
  /** Physical parameters of the simulated arm. */
  model: Partial<SimModelOptions>;
  /** Faults in force from the start. */
  faults: Fault[];
  /** Told the first time each kind of problem happens (later ones are only counted). */
  onFirst: (kind: string, message: string) => void;
  /**
   * Commands per second the controller accepts, sustained (a top-level frame or a whole `{…}`
   * group is one command; stops, `#255PDST!` included, are never limited; dropped input costs
   * nothing). Beyond it commands are dropped, never queued, and the first drop of a run is
   * answered `$ERR:rate limit!`.
   */
  commandRate: number;
  /** Commands accepted at once after a quiet spell (the bucket's size). */
  commandBurst: number;
  /** Largest control payload (or serial chunk) read, bytes; a bigger one is refused whole. */
  maxPayloadBytes: number;
}

export const DEFAULT_SIM_RUNNER_OPTIONS: SimRunnerOptions = {
  rate: 50,
  healthRate: 2,
  stamp: true,
  maxCatchUpMs: 500,
  maxErrorsPerChunk: INPUT.maxErrorsPerChunk,
  random: Math.random,
  model: {},
  faults: [],
  onFirst: () => {},
  commandRate: INPUT.commandRate,
  commandBurst: INPUT.commandBurst,
  maxPayloadBytes: INPUT.maxPayloadBytes,
};

export const MAX_STATE_RATE = 1000;
