/** What every section receives and returns; the orchestrator (../run.ts) turns it into the report. */
import type { MosquittoService, InfluxService } from '../../tests/helpers/services.ts';

export interface BenchContext {
  quick: boolean;
  /** Results folder (bench/results) and this run's stamp (file name prefix). */
  resultsDir: string;
  stamp: string;
  /** Where child-process logs go for this run (a temp dir, removed unless --keep-logs). */
  logDir: string;
  broker: MosquittoService;
  influx: InfluxService;
  log(message: string): void;
  /** The built HUD the page sections serve (`--hud-dist`; default apps/web/dist). */
  hudDist: string;
  /** Length of the soak section (`--soak-minutes`, default 30). */
  soakMinutes: number;
  /** Chromium's flags for the page sections: software WebGL, or the GPU's with `--gpu`. */
  chromiumArgs: readonly string[];
}

/** One line of the table: a figure, its baseline measured in the same run, and the target. */
export interface Row {
  figure: string;
  value: string;
  baseline: string;
  target: string;
  /** true/false when the target is checkable, null when it is only reported. */
  met: boolean | null;
}

export interface Plot {
  /** File name inside the results dir. */
  file: string;
  title: string;
}

export interface SectionOutput {
  rows: Row[];
  plots?: Plot[];
  /** Settings this section ran with (recorded in the JSON). */
  settings: Record<string, unknown>;
  /** Raw figures for the JSON. */
  data: Record<string, unknown>;
}

export type SectionResult =
  | ({ status: 'ok'; durationS: number } & SectionOutput)
  | {
      status: 'skipped' | 'failed';
      reason: string;
      durationS: number;
      settings?: Record<string, unknown>;
    };

export interface Section {
  id: string;
  title: string;
  /** Returns a reason to skip (e.g. the HUD is not built), or null to run. */
  precheck?(): string | null;
  run(ctx: BenchContext): Promise<SectionOutput>;
}

/** Formats a number with `digits` decimals, '—' for NaN/undefined. */
export const fmt = (v: number | undefined, digits = 2): string =>
  v === undefined || !Number.isFinite(v) ? '—' : v.toFixed(digits);
