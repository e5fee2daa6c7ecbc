/**
 * The scene runtime hosted on the page's main thread (where no worker can draw: `?render=main`,
 * or the render worker failed before its first frame): the same host and runtime as the worker's
 * (./sceneHost.ts), behind a MessageChannel, so the page side (./SceneClient.ts) sends the same
 * messages and reads the same reports. The runtime draws on the page's own canvas (its pixels can
 * be read back) and, as the main-thread view always did, draws 8 frames back to back first so
 * the resolution fits the machine before the page waits on it; its frames are not paced.
 */
import type { SceneChannel, SceneHosting } from './SceneClient.ts';
import { hostScene } from './sceneHost.ts';
import type { FromWorker, ToWorker } from './messages.ts';
import type { SceneRuntime } from './SceneRuntime.ts';

/** The runtime on the page's main thread (./SceneClient.ts's `hosting`). */
export const IN_THREAD_HOSTING: SceneHosting = {
  thread: 'main',
  offscreen: false,
  open: (canvas) => openInThreadScene(canvas),
};

/** A channel to a runtime on this thread drawing on `canvas`, and the runtime (once `init`). */
export function openInThreadScene(
  canvas: HTMLCanvasElement,
): SceneChannel & { readonly runtime: SceneRuntime | null } {
  const { port1, port2 } = new MessageChannel();
  const host = hostScene(port2 as unknown as Parameters<typeof hostScene>[0], {
    canvas,
    pacing: () => ({ warmupFrames: 8 }),
  });
  const channel = {
    onmessage: null as ((e: MessageEvent<FromWorker>) => void) | null,
    onerror: null as ((e: ErrorEvent) => void) | null,
    postMessage(m: ToWorker, transfer: Transferable[] = []): void {
      port1.postMessage(m, transfer);
    },
    terminate(): void {
      host.dispose();
      port1.close();
      port2.close();
    },
    get runtime(): SceneRuntime | null {
      return host.runtime;
    },
  };
  port1.onmessage = (e: MessageEvent<FromWorker>) => channel.onmessage?.(e);
  return channel;
}
