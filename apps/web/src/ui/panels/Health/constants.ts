import { TEMP_CRITICAL_C, TEMP_WARNING_C, VOLTAGE_MIN_V } from '@armtwin/protocol';

/** One line colour per servo (000–007; track6 has 7), in the charts and the table's swatches. */
export const SERVO_COLOURS = [
  '#60a5fa',
  '#f59e0b',
  '#34d399',
  '#f472b6',
  '#a78bfa',
  '#e5e7eb',
  '#fb7185',
  '#2dd4bf',
];

/** Threshold lines drawn on the charts (PROTOCOL.md §5). */
export const TEMP_LINES = [
  { value: TEMP_WARNING_C, colour: '#f97316' },
  { value: TEMP_CRITICAL_C, colour: '#ef4444' },
];
export const VOLT_LINES = [{ value: VOLTAGE_MIN_V, colour: '#ef4444' }];

export const CHART_HEIGHT = 92;
/** How often the charts look for new rows, ms (health arrives at 2 Hz). */
export const CHART_POLL_MS = 200;

/** Dash pattern of a predicted temperature line (px on, px off). */
export const PREDICTED_DASH = [4, 3];
