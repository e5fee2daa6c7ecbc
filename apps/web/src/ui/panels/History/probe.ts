/**
 * What the History panel's charts show, for the end-to-end tests and the console
 * (`window.__armtwin.history`): per chart, the series labels and their point counts.
 * Written when a chart is drawn; read-only by convention.
 */
import type { TeachError } from '@armtwin/motion';

export interface ChartProbe {
  labels: string[];
  /** Non-null points per series. */
  points: number[];
  /** Largest value per series (NaN when it has none). */
  max: number[];
  /** Labels of the moments marked (the thermal model's early warnings). */
  markers: string[];
  /** The replay's instant marked on it now, epoch ms (null: none). */
  replayAt: number | null;
}

/** The last "Make plan from this range": samples read, waypoints made, error (MakePlan.tsx). */
export interface TeachProbe {
  samples: number;
  waypoints: number;
  error: TeachError;
}

export const historyProbe: { charts: Record<string, ChartProbe>; teach?: TeachProbe | null } = {
  charts: {},
};
