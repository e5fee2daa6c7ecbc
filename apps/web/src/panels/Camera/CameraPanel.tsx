/**
 * Cameras: every camera announced for the selected arm (PROTOCOL.md §7, src/cameras/CameraHub.ts),
 * each a `Camera <label>` region drawn by its own player outside React. Folds away like the
 * Connection panel.
 */
import './camera.css';
import { useHud } from '../../hud/HudContext.ts';
import { useSampled } from '../../hud/useSampled.ts';
import { CameraView } from './CameraView.tsx';

export function CameraPanel() {
  const { cameras, cameraScreens, settings } = useHud();
  // Re-render when a camera comes, changes or goes, or the 3D view looks through another.
  const viewing = useSampled(() => `${cameras.version}:${cameraScreens.viewing}`).split(':')[1];
  const list = cameras.list;
  const credentials = { username: settings.username, password: settings.password };
  return (
    <details className="panel cameras" open>
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
            credentials={credentials}
            pictures={cameras.pictures}
            viewing={viewing === c.camId}
            {...(c.pose
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
