/**
 * One camera: a region named `Camera <label>` (the label is text only), the canvas its decoder
 * draws into (src/core/cameras/CameraDecoders.ts, outside React; this view only hosts it), and a line
 * sampled four times a second: the age of the last frame, or "camera offline since HH:MM:SS"
 * while the stream is gone. For an operator, the calibration below it (./Calibration.tsx).
 */
import { useEffect, useRef } from 'react';
import { useSampled } from '../../hud/useSampled.ts';
import type { ArmCamera } from '../../../core/cameras/CameraHub.ts';
import type { CameraDecoders } from '../../../core/cameras/CameraDecoders.ts';
import { hasVideoDecoder } from '../../../core/cameras/H264Player.ts';
import { pickStream } from '../../../core/cameras/streamUrl.ts';
import { Calibration, type CalibrationActions } from './Calibration.tsx';
import { ageWords, offlineWords } from './words.ts';

interface Props {
  camera: ArmCamera;
  decoders: CameraDecoders;
  /** Whether the 3D view looks through this camera now. */
  viewing: boolean;
  /** Toggles "view through this camera" (absent: the camera has no pose). */
  onViewThrough?: () => void;
  /** What an operator may do to the camera's calibration (absent: nothing). */
  calibration?: CalibrationActions;
}

export function CameraView({ camera, decoders, viewing, onViewThrough, calibration }: Props) {
  const hostRef = useRef<HTMLDivElement>(null);
  const kind = pickStream(camera, hasVideoDecoder())?.kind ?? null;
  const camId = camera.camId;

  useEffect(() => {
    const host = hostRef.current;
    if (!host) return;
    const canvas = decoders.canvasOf(camId);
    host.appendChild(canvas);
    return () => canvas.remove();
  }, [decoders, camId]);

  const snap = useSampled(() => {
    const s = decoders.stats(camId);
    const now = Date.now();
    return {
      dropped: s?.dropped ?? 0,
      line: !s
        ? 'connecting…'
        : s.offlineSince
          ? offlineWords(s.offlineSince, s.reason)
          : s.lastFrameAt
            ? ageWords(now - s.lastFrameAt)
            : 'connecting…',
      offline: s ? s.offlineSince > 0 : false,
    };
  });

  return (
    <section
      className={snap.offline ? 'camera-view offline' : 'camera-view'}
      aria-label={`Camera ${camera.label}`}
      data-camid={camId}
      data-kind={kind ?? 'none'}
    >
      <div className="camera-head">
        <h3 className="camera-label">{camera.label}</h3>
        {onViewThrough && (
          <button type="button" aria-pressed={viewing} onClick={onViewThrough}>
            {viewing ? 'Back to the 3D view' : 'View through this camera'}
          </button>
        )}
      </div>
      {kind ? (
        <div ref={hostRef} className="camera-picture" />
      ) : (
        <p className="error">No stream this page can play.</p>
      )}
      <p className={snap.offline ? 'camera-age error' : 'camera-age dim'} data-testid="camera-age">
        {snap.line}
        {snap.dropped > 0 && <span className="dim"> · {snap.dropped} dropped</span>}
      </p>
      {calibration && kind && (
        <Calibration
          camera={camera}
          viewing={viewing}
          actions={calibration}
          picture={() => decoders.canvasOf(camId)}
        />
      )}
    </section>
  );
}
