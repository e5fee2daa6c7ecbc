/**
 * The scene runtime hosted on the page's main thread (where no worker can draw: `?render=main`,
 * or the render worker failed before its first frame): the same host and runtime as the worker's
 * (./sceneHost.ts), behind a port pair on this thread, so the page side (./SceneClient.ts) sends
 * the same messages and reads the same reports. The runtime draws on the page's own canvas (its pixels can
 * be read back) and, as the main-thread view always did, draws 8 frames back to back first so
 * the resolution fits the machine before the page waits on it; its frames are not paced.
 */
import type { SceneChannel, SceneHosting } from './SceneClient.ts';
import { hostScene, type ScenePort } from './sceneHost.ts';
import type { FromWorker, ToWorker } from './messages.ts';
import type { SceneRuntime } from './SceneRuntime.ts';

/** The runtime on the page's main thread (./SceneClient.ts's `hosting`). */
export const IN_THREAD_HOSTING: SceneHosting = {
  thread: 'main',
  offscreen: false,
  open: (canvas) => openInThreadScene(canvas),
};

/**
 * A channel to a runtime on this thread drawing on `canvas`, and the runtime (once `init`).
 * A port pair on this thread rather than a MessageChannel: a message is delivered in a microtask,
 * so a frame's report (and the render hooks after it) comes before the browser composites that
 * frame and the canvas's pixels can still be read back then; what the page sends is copied as
 * `postMessage` would (`structuredClone`), so later changes to the page's arrays do not leak in.
 */
export function openInThreadScene(
  canvas: HTMLCanvasElement,
): SceneChannel & { readonly runtime: SceneRuntime | null } {
  let open = true;
  const port: ScenePort = {
    onmessage: null,
    postMessage(m: FromWorker): void {
      queueMicrotask(() => {
        if (open) channel.onmessage?.(new MessageEvent('message', { data: m }));
      });
    },
  };
  const host = hostScene(port, { canvas, pacing: () => ({ warmupFrames: 8 }) });
  const channel = {
    onmessage: null as ((e: MessageEvent<FromWorker>) => void) | null,
    onerror: null as ((e: ErrorEvent) => void) | null,
    postMessage(m: ToWorker, transfer: Transferable[] = []): void {
      const data = structuredClone(m, { transfer });
      queueMicrotask(() => {
        if (open) port.onmessage?.(new MessageEvent('message', { data }));
      });
    },
    terminate(): void {
      open = false;
      host.dispose();
    },
    get runtime(): SceneRuntime | null {
      return host.runtime;
    },
  };
  return channel;
}
