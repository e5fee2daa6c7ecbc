/**
 * Where the 3D view is drawn (`?render=`): `worker` draws it in a Web Worker through an
 * OffscreenCanvas (scene/render/), so WebGL never holds up the page's main thread; `main`
 * draws it on the page's thread (scene/Viewer.ts). A browser without
 * `HTMLCanvasElement.transferControlToOffscreen` (or without module workers) always gets `main`.
 * Pure.
 */
import type { RenderThread } from '../scene/SceneView.ts';

export interface RenderThreadOptions {
  /** Used when the query does not say. */
  defaultThread: RenderThread;
}

/**
 * `worker` wherever the browser can hand a canvas to a worker; if the worker then fails before
 * its first frame the page falls back to `main` by itself (scene/render/FallbackSceneView.ts).
 * `?render=main` keeps the view on the page's thread (the page then holds the robot's meshes and
 * the view's pixels can be read back, which some end-to-end checks and console users rely on).
 */
export const DEFAULT_RENDER_THREAD_OPTIONS: RenderThreadOptions = { defaultThread: 'worker' };

export interface RenderChoice {
  thread: RenderThread;
  /** Why, in words for the Status panel ('' when the choice is the default that works). */
  note: string;
}

/** The render thread for `search` (the page's query) on a browser that `canOffscreen` or not. */
export function chooseRenderThread(
  search: string,
  canOffscreen: boolean,
  opts: RenderThreadOptions = DEFAULT_RENDER_THREAD_OPTIONS,
): RenderChoice {
  // The last one counts (a test runner's default, then what one test asks for).
  const asked = new URLSearchParams(search).getAll('render').at(-1);
  const wanted: RenderThread = asked === 'worker' || asked === 'main' ? asked : opts.defaultThread;
  if (wanted === 'worker' && !canOffscreen)
    return { thread: 'main', note: 'this browser cannot draw in a worker (no OffscreenCanvas)' };
  return { thread: wanted, note: '' };
}

/** What the Status panel says after the worker failed (`reason`) and the main thread took over. */
export function fallbackChoice(reason: string): RenderChoice {
  return { thread: 'main', note: `worker failed: ${reason}` };
}

/** Whether this browser can hand a canvas to a worker. */
export function canRenderOffscreen(): boolean {
  return (
    typeof Worker !== 'undefined' &&
    typeof OffscreenCanvas !== 'undefined' &&
    typeof HTMLCanvasElement !== 'undefined' &&
    'transferControlToOffscreen' in HTMLCanvasElement.prototype
  );
}
