/**
 * A serial line for gateway tests and the bench: a socat pseudo-terminal pair with a simulated
 * device (`armtwin sim --serial …`, or `--bus …` for an emulated servo bus) on its far end.
 * `start()` makes the pair and starts the device, resolved once it says `ready`; `stop()` takes
 * both away (the line "unplugged"). With `hand`, lines written by `hand()` go to the device's
 * stdin (`armtwin sim --bus … --hand`: its shafts moved as a hand would).
 */
import { spawn, type ChildProcess } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { armtwin, type Child } from './sim-helpers.ts';

export interface SerialLine {
  /** The gateway's end. */
  hostSide: string;
  start(): Promise<void>;
  stop(): Promise<void>;
  /** One line to the device's stdin (only with `hand`). */
  hand(line: string): void;
  /** What the device printed so far. */
  output(): string;
}

/**
 * `simArgs(armSide)` are the device's `armtwin` arguments; `ready` is the line it prints once it
 * listens on the port.
 */
export function serialLine(
  hostSide: string,
  armSide: string,
  simArgs: (armSide: string) => string[],
  ready: string,
  { hand = false }: { hand?: boolean } = {},
): SerialLine {
  let socat: ChildProcess | undefined;
  let device: Child | undefined;
  return {
    hostSide,
    async start() {
      socat = spawn(
        'socat',
        ['-d', '-d', `pty,raw,echo=0,link=${hostSide}`, `pty,raw,echo=0,link=${armSide}`],
        { stdio: 'ignore' },
      );
      const deadline = Date.now() + 5000;
      while (!(fs.existsSync(hostSide) && fs.existsSync(armSide))) {
        if (Date.now() > deadline) throw new Error('socat made no pty pair');
        await new Promise((r) => setTimeout(r, 50));
      }
      const c = (device = armtwin(simArgs(armSide), undefined, { stdin: hand }));
      while (!c.output().includes(ready)) {
        if (Date.now() > deadline + 15_000)
          throw new Error(`the simulated device did not start:\n${c.output()}`);
        await new Promise((r) => setTimeout(r, 50));
      }
    },
    async stop() {
      const s = socat;
      socat = undefined;
      if (s && s.exitCode === null) {
        const gone = new Promise((r) => s.once('exit', r));
        s.kill('SIGTERM');
        await gone;
      }
      await device?.stop('SIGKILL');
      device = undefined;
    },
    hand(line: string) {
      if (!device?.proc.stdin) throw new Error('this serial line was started without hand');
      device.proc.stdin.write(`${line}\n`);
    },
    output: () => device?.output() ?? '',
  };
}

/** What the emulated servo bus prints once it serves its end of the line. */
export const BUS_READY = 'simulated servo bus on the serial line';

/**
 * An emulated SO-101 (six STS3215 on a Feetech bus at 1 Mbaud, `armtwin sim --bus feetech
 * --profile so101`) on a pty pair `{dir}/{name}-host` ⇄ `{dir}/{name}-arm`; `extra` are more sim
 * arguments (a `--bus-fault`), `hand` moves its shafts from `hand()` (`--hand`).
 */
export function so101BusLine(
  dir: string,
  name: string,
  { hand = false, extra = [] }: { hand?: boolean; extra?: string[] } = {},
): SerialLine {
  return serialLine(
    path.join(dir, `${name}-host`),
    path.join(dir, `${name}-arm`),
    (armSide) => [
      ...[
        'sim',
        '--bus',
        'feetech',
        '--serial',
        armSide,
        '--baud',
        '1000000',
        '--profile',
        'so101',
      ],
      ...(hand ? ['--hand'] : []),
      ...extra,
    ],
    BUS_READY,
    { hand },
  );
}
