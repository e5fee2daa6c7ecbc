/**
 * One camera: a region named `Camera <label>` (the label is text only), the canvas its player
 * draws into (outside React), and a line sampled four times a second: the age of the last frame,
 * or "camera offline since HH:MM:SS" while the stream is gone.
 */
import { useEffect, useRef } from 'react';
import { useSampled } from '../../hud/useSampled.ts';
import type { ArmCamera, CameraPicture } from '../../cameras/CameraHub.ts';
import type { CameraPlayer, CameraPlayerStats } from '../../cameras/CameraPlayer.ts';
import { H264Player, hasVideoDecoder } from '../../cameras/H264Player.ts';
import { MjpegPlayer } from '../../cameras/MjpegPlayer.ts';
import { pickStream, usableUrl, type CameraCredentials } from '../../cameras/streamUrl.ts';
import { ageWords, offlineWords } from './words.ts';

interface Props {
  camera: ArmCamera;
  credentials: CameraCredentials;
  /** Where the player's picture is registered for the 3D view's screens. */
  pictures: Map<string, CameraPicture>;
  /** Whether the 3D view looks through this camera now. */
  viewing: boolean;
  /** Toggles "view through this camera" (absent: the camera has no pose). */
  onViewThrough?: () => void;
}

export function CameraView({ camera, credentials, pictures, viewing, onViewThrough }: Props) {
  const canvasRef = useRef<HTMLCanvasElement>(null);
  const playerRef = useRef<CameraPlayer | null>(null);
  const stream = pickStream(camera, hasVideoDecoder());
  const url = stream?.url ?? '';
  const kind = stream?.kind ?? null;
  const { username, password } = credentials;

  useEffect(() => {
    const canvas = canvasRef.current;
    if (!canvas || !kind) return;
    const u = usableUrl({ url, kind });
    if (!u) return;
    const creds = { username, password };
    const player =
      kind === 'h264-ws' ? new H264Player(canvas, u, creds) : new MjpegPlayer(canvas, u, creds);
    playerRef.current = player;
    const picture: CameraPicture = { canvas, frames: () => player.stats.frames };
    pictures.set(camera.camId, picture);
    player.start();
    return () => {
      player.dispose();
      if (playerRef.current === player) playerRef.current = null;
      if (pictures.get(camera.camId) === picture) pictures.delete(camera.camId);
    };
  }, [url, kind, username, password, pictures, camera.camId]);

  const snap = useSampled(() => {
    const s: CameraPlayerStats | undefined = playerRef.current?.stats;
    const now = Date.now();
    return {
      frames: s?.frames ?? 0,
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
      data-camid={camera.camId}
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
        <canvas ref={canvasRef} className="camera-canvas" width={640} height={480} />
      ) : (
        <p className="error">No stream this page can play.</p>
      )}
      <p className={snap.offline ? 'camera-age error' : 'camera-age dim'} data-testid="camera-age">
        {snap.line}
        {snap.dropped > 0 && <span className="dim"> · {snap.dropped} dropped</span>}
      </p>
    </section>
  );
}
