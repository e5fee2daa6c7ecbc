/** The wizard's result for one servo beside the profile's values in force, and Save. */
import type { CalibrationResult, ProfileServo, ServoCalibrationFields } from '@armtwin/robot';

interface Props {
  servo: ProfileServo;
  result: CalibrationResult;
  onSave(fields: ServoCalibrationFields): void;
  onRestart(): void;
}

const ROWS = [
  ['polarity', 'direction'],
  ['offset', 'zero offset, °'],
  ['min', 'min, °'],
  ['max', 'max, °'],
] as const;

export function CalibrationReview({ servo, result, onSave, onRestart }: Props) {
  if (!result.ok)
    return (
      <>
        <p className="note error" role="alert" data-testid="calibration-error">
          {result.error}
        </p>
        <button type="button" onClick={onRestart}>
          Start over
        </button>
      </>
    );
  const f = result.fields;
  return (
    <>
      <table className="calibration-result" data-testid="calibration-result">
        <thead>
          <tr>
            <th />
            <th>now</th>
            <th>new</th>
          </tr>
        </thead>
        <tbody>
          {ROWS.map(([key, label]) => (
            <tr key={key} className={servo[key] === f[key] ? '' : 'changed'}>
              <th scope="row">{label}</th>
              <td>{servo[key]}</td>
              <td data-testid={`calibration-new-${key}`}>{f[key]}</td>
            </tr>
          ))}
        </tbody>
      </table>
      <div className="row">
        <button type="button" className="primary" onClick={() => onSave(f)}>
          Save to profile
        </button>
        <button type="button" onClick={onRestart}>
          Start over
        </button>
      </div>
    </>
  );
}
