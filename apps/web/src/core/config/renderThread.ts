/**
 * Where the 3D view is drawn (`?render=`): `worker` draws it in a Web Worker through an
 * OffscreenCanvas (scene/render/), so WebGL never holds up the page's main thread; `main`
 * draws it on the page's thread (scene/render/inThreadScene.ts). A browser without
 * `HTMLCanvasElement.transferControlToOffscreen` (or without module workers) always gets `main`.
 * With software WebGL the worker paces its frames (scene/FramePacer.ts `SOFTWARE_PACING`), so
 * drawing on the CPU never takes the machine's cores from the stop, MQTT and the rest;
 * `?frames=full` draws every frame anyway (a strong CPU without a GPU). Pure.
 */
/** Where the 3D view is drawn: 'main' (the page's thread) or 'worker' (OffscreenCanvas). */
export type RenderThread = 'main' | 'worker';

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
  /** Whether the worker paces software WebGL's frames (`?frames=full`: it does not). */
  pace: boolean;
}

/** The render thread for `search` (the page's query) on a browser that `canOffscreen` or not. */
export function chooseRenderThread(
  search: string,
  canOffscreen: boolean,
  opts: RenderThreadOptions = DEFAULT_RENDER_THREAD_OPTIONS,
): RenderChoice {
  // The last one counts (a test runner's default, then what one test asks for).
  const query = new URLSearchParams(search);
  const asked = query.getAll('render').at(-1);
  const wanted: RenderThread = asked === 'worker' || asked === 'main' ? asked : opts.defaultThread;
  const pace = query.getAll('frames').at(-1) !== 'full';
  if (wanted === 'worker' && !canOffscreen)
    return {
      thread: 'main',
      note: 'this browser cannot draw in a worker (no OffscreenCanvas)',
      pace,
    };
  return { thread: wanted, note: '', pace };
}

/** What the Status panel says after the worker failed (`reason`) and the main thread took over. */
export function fallbackChoice(reason: string, pace: boolean): RenderChoice {
  return { thread: 'main', note: `worker failed: ${reason}`, pace };
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
