/**
 * A camera's calibration, for an operator (docs/protocol.md § Cameras): its pose (position and
 * the point it looks at, mm in the arm's frame) and vertical field of view, set by eye while the
 * 3D view looks through the camera (the view follows each change), or solved from four or more
 * clicked points: pick a twin point (a link of the live twin, where it is drawn now: jog the arm
 * and pick the tip again for another point), click where it is in the picture. Saved retained
 * for every viewer; "Back to the announced pose" clears it.
 */
import { useEffect, useState } from 'react';
import { MIN_MATCHES, solveCamera, type PointMatch, type Vec3 } from '@armtwin/camera/client';
import {
  DEFAULT_FOV_DEG,
  placementOf,
  type ArmCamera,
  type CameraPlacement,
} from '../../../core/cameras/CameraHub.ts';
import type { TwinPoint } from '../../../scene/twinPoints.ts';
import { tipName } from '../../../scene/twinPoints.ts';
import { clockTime } from './words.ts';
import { draftFromPlacement, placementFromDraft, AXES, type Draft } from './draft.ts';

export interface CalibrationActions {
  /** Publishes the calibration (null clears it); false when it could not be sent. */
  save(placement: CameraPlacement | null): boolean;
  /** Shows `placement` in the 3D view while it looks through this camera (null: the saved one). */
  preview(placement: CameraPlacement | null): void;
  /** The twin's points as drawn now. */
  twinPoints(): TwinPoint[];
}

interface Props {
  camera: ArmCamera;
  viewing: boolean;
  actions: CalibrationActions;
  /** The canvas the camera's picture is drawn into (clicked for the four points). */
  picture(): HTMLCanvasElement;
}

/** Where an unposed camera starts: beside the arm, looking at its middle. */
const START: CameraPlacement = {
  pose: { position: [600, -400, 450], lookAt: [0, 0, 200] },
  fovDeg: DEFAULT_FOV_DEG,
};
/** A fit worse than this many picture heights is reported as poor. */
const POOR_FIT = 0.02;

export function Calibration({ camera, viewing, actions, picture }: Props) {
  const placement = placementOf(camera) ?? START;
  const placementKey = JSON.stringify(placement);
  const [open, setOpen] = useState(false);
  const [draft, setDraft] = useState<Draft>(() => draftFromPlacement(placement));
  const [message, setMessage] = useState('');
  const [points, setPoints] = useState<PointMatch[]>([]);
  const [names, setNames] = useState<string[]>([]);
  const [pick, setPick] = useState('');
  // A calibration that arrives (saved here or elsewhere) becomes the draft.
  const [seenKey, setSeenKey] = useState(placementKey);
  if (seenKey !== placementKey) {
    setSeenKey(placementKey);
    setDraft(draftFromPlacement(placement));
  }

  // While open and looking through this camera, the 3D view follows the draft.
  const drafted = placementFromDraft(draft);
  const draftedKey = drafted ? JSON.stringify(drafted) : '';
  useEffect(() => {
    if (!open || !viewing) return;
    actions.preview(draftedKey ? (JSON.parse(draftedKey) as CameraPlacement) : null);
    return () => actions.preview(null);
  }, [open, viewing, draftedKey, actions]);

  // While open, a click on the picture matches the picked twin point to that spot.
  useEffect(() => {
    if (!open) return;
    const canvas = picture();
    const onClick = (e: MouseEvent) => {
      const r = canvas.getBoundingClientRect();
      if (r.width === 0 || r.height === 0) return;
      const image: [number, number] = [
        (e.clientX - r.left) / r.width,
        (e.clientY - r.top) / r.height,
      ];
      const twin = actions.twinPoints().find((p) => p.name === pick);
      if (!twin) return setMessage('Pick a twin point first.');
      setPoints((ps) => [...ps, { world: [...twin.mm] as Vec3, image }]);
      setMessage('');
    };
    canvas.addEventListener('click', onClick);
    canvas.classList.add('picking');
    return () => {
      canvas.removeEventListener('click', onClick);
      canvas.classList.remove('picking');
    };
  }, [open, picture, actions, pick]);

  const onToggle = (e: React.SyntheticEvent<HTMLDetailsElement>) => {
    const isOpen = e.currentTarget.open;
    setOpen(isOpen);
    if (!isOpen) return;
    const twin = actions.twinPoints();
    setNames(twin.map((p) => p.name));
    setPick((prev) => prev || tipName(twin));
  };

  const solve = () => {
    const canvas = picture();
    try {
      const r = solveCamera(points, {
        aspect: canvas.width / canvas.height,
        ...(drafted ? { guess: drafted } : {}),
      });
      setDraft(draftFromPlacement({ pose: r.pose, fovDeg: r.fovDeg }));
      const px = (r.rms * canvas.height).toFixed(1);
      setMessage(
        r.rms > POOR_FIT
          ? `Poor fit: the points are ${px} px off on average; check them, or add more.`
          : `Solved: the points fit within ${px} px. Save to keep it.`,
      );
    } catch (err) {
      setMessage(err instanceof Error ? err.message : String(err));
    }
  };

  const save = (p: CameraPlacement | null) => {
    try {
      setMessage(actions.save(p) ? (p ? 'Saved.' : 'Cleared.') : 'Not sent: not connected.');
    } catch (err) {
      setMessage(err instanceof Error ? err.message : String(err));
    }
  };

  const field = (key: keyof Draft, label: string, step: number) => (
    <input
      type="number"
      step={step}
      aria-label={label}
      value={draft[key]}
      onChange={(e) => setDraft({ ...draft, [key]: e.currentTarget.value })}
    />
  );

  const c = camera.calibration;
  return (
    <details className="camera-calibrate" onToggle={onToggle}>
      <summary>Calibrate</summary>
      <p className="dim">
        {c ? `Calibrated by ${c.by} at ${clockTime(Date.parse(c.at))}.` : 'Announced pose.'}
        {!viewing && ' View through this camera to see the twin over the picture.'}
      </p>
      <div className="calib-grid">
        <span>Position, mm</span>
        {AXES.map((a) => field(`p${a}`, `Position ${a} (mm)`, 10))}
        <span>Looks at, mm</span>
        {AXES.map((a) => field(`l${a}`, `Looks at ${a} (mm)`, 10))}
        <span>Field of view, °</span>
        {field('fov', 'Field of view (degrees)', 0.5)}
      </div>
      <div className="calib-points">
        <label>
          Twin point{' '}
          <select value={pick} onChange={(e) => setPick(e.currentTarget.value)}>
            {names.map((n) => (
              <option key={n} value={n}>
                {n}
              </option>
            ))}
          </select>
        </label>{' '}
        <span className="dim" data-testid="calib-point-count">
          {points.length} points ({MIN_MATCHES} needed): click where the twin point is in the
          picture
        </span>
        <div className="calib-actions">
          <button type="button" disabled={points.length < MIN_MATCHES} onClick={solve}>
            Solve from the points
          </button>
          <button type="button" disabled={points.length === 0} onClick={() => setPoints([])}>
            Forget the points
          </button>
        </div>
      </div>
      <div className="calib-actions">
        <button type="button" disabled={!drafted} onClick={() => save(drafted)}>
          Save calibration
        </button>
        <button type="button" disabled={!c} onClick={() => save(null)}>
          Back to the announced pose
        </button>
      </div>
      {message && (
        <p className="dim" role="status">
          {message}
        </p>
      )}
    </details>
  );
}
