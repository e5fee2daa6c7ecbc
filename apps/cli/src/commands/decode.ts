import type { Command } from 'commander';
import { createReader, type Frame, type ReaderError } from '@armtwin/protocol';

/** One JSON line per frame; a group's frames carry `group` (1, 2, …) to show they belong together. */
export function decodeStream(
  input: NodeJS.ReadableStream,
  write: (line: string) => void,
): Promise<void> {
  let groups = 0;
  const print = (frame: Frame, group?: number) =>
    write(JSON.stringify(group === undefined ? frame : { ...frame, group }) + '\n');
  const reader = createReader({
    onFrame: (frame) => print(frame),
    onGroup: (group) => {
      groups++;
      for (const frame of group.frames) print(frame, groups);
    },
    onError: (error: ReaderError) =>
      write(
        JSON.stringify({
          type: 'error',
          kind: error.kind,
          reason: error.message,
          text: error.text,
        }) + '\n',
      ),
  });
  return new Promise((resolve, reject) => {
    input.on('data', (chunk: Buffer | string) =>
      reader.feed(typeof chunk === 'string' ? chunk : new Uint8Array(chunk)),
    );
    input.on('end', () => {
      reader.flush();
      resolve();
    });
    input.on('error', reject);
  });
}

export function registerDecode(program: Command): void {
  program
    .command('decode')
    .description(
      'decode raw frames from stdin into one JSON object per line (streams as frames arrive)',
    )
    .addHelpText(
      'after',
      `
Examples:
  mosquitto_sub -t 'arm/+/status' | armtwin decode
  printf '$TIM:1700000000000!{#000P1500!#001P1612!}#001T045V7400!' | armtwin decode

Each frame prints as {"type": …, fields…}; input that was dropped prints as
{"type":"error","kind":…,"reason":…,"text":…}.`,
    )
    .action(() => decodeStream(process.stdin, (line) => process.stdout.write(line)));
}
