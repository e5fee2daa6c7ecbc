/**
 * `PUT /api/robots/<name>/calibration` (an operator's right; anyone in the anonymous local
 * demo): the calibration wizard's result, `{"servos":[{"id","polarity","offset","min","max"}]}`,
 * written into `<models>/<name>/profile.json` (the first models folder holding it). The body is
 * checked (`parseCalibrationRequest`), applied to the profile as it is on disk now
 * (`applyCalibration`, which runs the profile parser on the result) and written with a backup
 * of the old file (`replaceProfileFile`). A bus gateway running that profile watches the file
 * and takes the new calibration at once (docs/arm-side.md).
 *
 * Answers JSON: 200 `{ok, profile, backup}`; 400 `{ok:false, errors}` for a body or result the
 * parser refuses; 401/403 for a missing or non-operator log-in; 404 for an unknown robot; 413
 * for a body over `MAX_CALIBRATION_REQUEST_BYTES`.
 */
import {
  applyCalibration,
  MAX_CALIBRATION_REQUEST_BYTES,
  parseCalibrationRequest,
} from '@armtwin/robot';
import { profileWriteRoute, type RobotWriteOptions } from './robot-write.ts';

export const calibrationRoute = (o: RobotWriteOptions) =>
  profileWriteRoute(o, {
    label: 'calibration',
    maxBytes: MAX_CALIBRATION_REQUEST_BYTES,
    request(json) {
      const r = parseCalibrationRequest(json);
      return r.ok ? { ok: true, value: r.servos } : r;
    },
    apply(raw, servos) {
      const r = applyCalibration(raw, servos);
      return r.ok ? { ok: true, value: { raw: r.raw, told: { profile: r.raw } } } : r;
    },
    refusedAs: 'profile',
  });
