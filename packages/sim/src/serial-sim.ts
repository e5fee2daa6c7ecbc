/**
 * The simulated controller on a serial line, as the real firmware sits behind the gateway:
 * no `$TIM` stamps (the gateway adds them), no presence, no fault topic (faults by flag only).
 * Used by `armtwin sim --serial PATH` and as the fake controller of the gateway's tests.
 */
import { SerialPort } from 'serialport';
import { SYSTEM_CLOCK } from '@armtwin/protocol';
import { SimRunner, type SimRunnerOptions } from './runner.ts';

export interface SerialSimOptions extends Partial<SimRunnerOptions> {
  path: string;
  baudRate: number;
}

export interface SerialSim {
  runner: SimRunner;
  /** Resolves when the line closes under us (the device or pty went away). */
  closed: Promise<string>;
  stop(): Promise<void>;
}

export async function startSerialSim(options: SerialSimOptions): Promise<SerialSim> {
  const port = new SerialPort({ path: options.path, baudRate: options.baudRate, autoOpen: false });
  await new Promise<void>((resolve, reject) => port.open((err) => (err ? reject(err) : resolve())));
  const runner = new SimRunner({ send: (payload) => void port.write(payload) }, SYSTEM_CLOCK, {
    ...options,
    stamp: false,
  });
  port.on('data', (chunk: Buffer) => runner.receive(chunk));
  port.on('error', (err) => options.onFirst?.('serial', err.message));
  const closed = new Promise<string>((resolve) =>
    port.on('close', (err: Error | null) => {
      runner.stop();
      resolve(err?.message ?? 'closed');
    }),
  );
  runner.start();
  return {
    runner,
    closed,
    stop: async () => {
      runner.stop();
      if (port.isOpen) await new Promise<void>((resolve) => port.close(() => resolve()));
    },
  };
}
