/**
 * Hosts the scene runtime (./SceneRuntime.ts) behind a message port: the page's `ToWorker`
 * messages in, `FromWorker` reports out (./messages.ts). The same host runs in the render worker
 * (./renderWorker.ts, on the worker's own scope) and on the page's main thread behind a
 * port pair (./inThreadScene.ts); only where the canvas comes from and how frames are paced
 * differ, and the host is told both.
 */
import type { FramePacerOptions } from '../FramePacer.ts';
import { webglRenderer, isSoftwareRenderer } from '../webglInfo.ts';
import type { FromWorker, ToWorker } from './messages.ts';
import { SceneRuntime } from './SceneRuntime.ts';

/** A worker's scope or an in-thread port: what the host listens on and posts to. */
export interface ScenePort {
  postMessage(m: FromWorker): void;
  onmessage: ((e: MessageEvent<ToWorker>) => void) | null;
}

export interface SceneHostOptions {
  /** The canvas to draw on: the one `init` carries (a worker's OffscreenCanvas), else this. */
  canvas?: HTMLCanvasElement;
  /** How to pace frames, given whether WebGL runs in software and the page's `pace`. */
  pacing(software: boolean, pace: boolean): Partial<FramePacerOptions>;
}

export interface SceneHost {
  /** The runtime once `init` arrived (null before). */
  readonly runtime: SceneRuntime | null;
  /** Stops the runtime and stops listening. */
  dispose(): void;
}

export function hostScene(port: ScenePort, opts: SceneHostOptions): SceneHost {
  const post = (m: FromWorker): void => port.postMessage(m);
  let scene: SceneRuntime | null = null;
  port.onmessage = (e) => {
    const m = e.data;
    try {
      switch (m.type) {
        case 'init': {
          const canvas = m.canvas ?? opts.canvas;
          if (!canvas) throw new Error('no canvas to draw on');
          const renderer = webglRenderer(m.canvas ? () => new OffscreenCanvas(1, 1) : undefined);
          const software = isSoftwareRenderer(renderer);
          scene = new SceneRuntime(canvas, software, m.dpr, post, opts.pacing(software, m.pace));
          scene.resize(m.width, m.height, m.dpr);
          post({ type: 'ready', software, renderer });
          break;
        }
        case 'resize':
          scene?.resize(m.width, m.height, m.dpr, m.seq);
          break;
        case 'zones':
          if (scene) post({ type: 'zones', names: scene.showZones(m.keepOut) });
          break;
        case 'frame':
          scene?.take(m);
          break;
        case 'extras':
          scene?.setExtras(m.objects, m.sceneObjects, m.hidden);
          break;
        case 'texture':
          if (scene) scene.setTexture(m.uuid, m.bitmap);
          else m.bitmap.close();
          break;
        case 'load': {
          const s = scene;
          if (!s) break;
          s.load(m.urdfUrl, m.joints, m.sibling).then(
            ({ failures, framed }) => {
              post({ type: 'loaded', id: m.id, failures, framed });
              s.start();
            },
            (err: unknown) =>
              post({
                type: 'loadFailed',
                id: m.id,
                message: err instanceof Error ? err.message : String(err),
              }),
          );
          break;
        }
      }
    } catch (err) {
      post({ type: 'error', message: err instanceof Error ? err.message : String(err) });
    }
  };
  return {
    get runtime() {
      return scene;
    },
    dispose() {
      port.onmessage = null;
      scene?.stop();
      scene = null;
    },
  };
}
