/**
 * Cameras: every camera announced for the selected arm (PROTOCOL.md §7, src/core/cameras/CameraHub.ts),
 * each a `Camera <label>` region showing the canvas its decoder draws into (outside React). Folds
 * away like the Connection panel; folded, a camera decodes only where the 3D view still shows it
 * (src/core/cameras/CameraDecoders.ts).
 */
import './camera.css';
import { useCameras, useSettings } from '../../hud/HudParts.ts';
import { useSampled } from '../../hud/useSampled.ts';
import { placementOf } from '../../../core/cameras/CameraHub.ts';
import { CameraView } from './CameraView.tsx';

export function CameraPanel() {
  const { hub: cameras, screens: cameraScreens } = useCameras();
  const settings = useSettings();
  // Re-render when a camera or its calibration changes, the 3D view looks through another, or
  // the page's role changes.
  const [, viewing, calibrate] = useSampled(
    () => `${cameras.version}:${cameraScreens.viewing}:${cameras.canCalibrate ? 1 : 0}`,
  ).split(':');
  const list = cameras.list;
  return (
    <details
      className="panel cameras"
      open
      onToggle={(e) => cameras.decoders.setPanelOpen(e.currentTarget.open)}
    >
      <summary>
        <h2>Cameras</h2>
        <span className="dim">{list.length}</span>
      </summary>
      {list.length === 0 ? (
        <p className="dim">No camera announced for this arm.</p>
      ) : (
        list.map((c) => (
          <CameraView
            key={c.camId}
            camera={c}
            decoders={cameras.decoders}
            viewing={viewing === c.camId}
            {...(calibrate === '1'
              ? {
                  calibration: {
                    save: (p) => cameras.saveCalibration(c.camId, p, settings.username),
                    preview: (p) => {
                      if (cameraScreens.viewing === c.camId) cameraScreens.preview(p);
                    },
                    twinPoints: () => cameraScreens.twinPoints(),
                  },
                }
              : {})}
            {...(placementOf(c)
              ? {
                  onViewThrough: () =>
                    cameraScreens.viewThrough(viewing === c.camId ? '' : c.camId),
                }
              : {})}
          />
        ))
      )}
    </details>
  );
}
