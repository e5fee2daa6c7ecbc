/** Robot profiles: format, parser, conversions, and the views other parts need. */
export * from './types.ts';
export * from './convert.ts';
export { parseProfile } from './parse.ts';
export {
  MAX_ZONES,
  MAX_KEEP_OUT_REQUEST_BYTES,
  applyKeepOut,
  type ApplyKeepOutResult,
} from './keep-out.ts';
export * from './servo-table.ts';
export * from './calibration.ts';
export * from './apply-calibration.ts';
export * from './announcement.ts';
export * from './lerobot-units.ts';
