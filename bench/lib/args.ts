/**
 * `npm run bench`'s command line, read with commander (as `armtwin` reads its own): the flags,
 * their help (`--help`), and a clear error for an unknown flag, an unknown section or a bad value.
 */
import path from 'node:path';
import { Command, CommanderError, InvalidArgumentError, Option } from 'commander';

export interface BenchArgs {
  quick: boolean;
  /** The sections named by `--only`, or null for the default set. */
  only: Set<string> | null;
  keepLogs: boolean;
  /** Rewrite BENCHMARKS.md (`--no-md`: not). */
  md: boolean;
  soakMinutes: number;
  hudDist: string;
  gpu: boolean;
}

/**
 * Reads `argv` (after the script's name). `--help` prints the usage and exits 0; anything it
 * cannot use throws, with the reason and the usage.
 */
export function parseBenchArgs(
  argv: readonly string[],
  sections: readonly string[],
  hudDist: string,
): BenchArgs {
  const program = new Command('npm run bench')
    .usage(`[-- --quick] [-- --only ${sections.join(',')}] [-- --keep-logs] [-- --no-md]`)
    .helpOption('-h, --help', 'show this help')
    .option('--quick', 'shorter runs (< 5 min): 5,000 pings at 1 kHz, short ramps and windows')
    .addOption(
      new Option(
        '--only <a,b>',
        'run only these sections (e.g. --only camera: the camera section alone, ≈ 2 min)',
      ).argParser((v) => {
        const only = new Set(v.split(',').filter(Boolean));
        const bad = [...only].filter((id) => !sections.includes(id));
        if (bad.length) throw new InvalidArgumentError(`unknown section(s): ${bad.join(', ')}`);
        return only;
      }),
    )
    .option('--keep-logs', 'keep child-process logs (printed at the end)')
    .option('--no-md', 'do not rewrite BENCHMARKS.md (the JSON and SVGs are still written)')
    .option(
      '--soak-minutes <n>',
      'length of the soak (default 30); the soak runs only when named: --only soak',
      (v) => {
        const n = Number(v);
        if (v.trim() === '' || !Number.isInteger(n) || n < 3)
          throw new InvalidArgumentError('a whole number ≥ 3');
        return n;
      },
    )
    .option(
      '--hud-dist <dir>',
      'serve this built HUD instead of apps/web/dist (e.g. a copy of an older build)',
      (v) => path.resolve(v),
    )
    .option(
      '--gpu',
      'page sections with hardware WebGL (Chromium on ANGLE/Vulkan) instead of SwiftShader',
    )
    .allowExcessArguments(false)
    .exitOverride()
    .configureOutput({ writeErr: () => {} });
  try {
    program.parse(argv, { from: 'user' });
  } catch (err) {
    if (err instanceof CommanderError && err.code === 'commander.helpDisplayed') process.exit(0);
    const why = err instanceof Error ? err.message.replace(/^error: /, '') : String(err);
    throw new Error(`${why}\n${program.helpInformation()}`, { cause: err });
  }
  const o = program.opts<Partial<BenchArgs>>();
  return {
    quick: o.quick === true,
    only: o.only ?? null,
    keepLogs: o.keepLogs === true,
    md: o.md !== false,
    soakMinutes: o.soakMinutes ?? 30,
    hudDist: o.hudDist ?? hudDist,
    gpu: o.gpu === true,
  };
}
