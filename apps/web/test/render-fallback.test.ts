/**
 * The 3D view falls back from the render worker to the main thread when the worker fails before
 * its first frame (scene/render/FallbackSceneView.ts), and says why (config/renderThread.ts).
 */
import { describe, expect, it } from 'vitest';
import * as THREE from 'three';
import { fallbackChoice } from '../src/core/config/renderThread.ts';
import { FallbackSceneView, type FailingView } from '../src/scene/render/FallbackSceneView.ts';
import type { RenderThread, SceneView } from '../src/scene/SceneView.ts';

/** A stand-in view: three's real scene graph, loads that resolve or reject on demand. */
function fakeView(thread: RenderThread) {
  const scene = new THREE.Scene();
  const world = new THREE.Group();
  scene.add(world);
  const loads: { url: string; resolve(): void; reject(e: Error): void }[] = [];
  const view = {
    thread,
    scene,
    world,
    camera: new THREE.PerspectiveCamera(),
    controls: { target: new THREE.Vector3(), update() {} },
    canvas: {} as HTMLCanvasElement,
    liveRobot: null,
    zones: { names: [] as string[] },
    ghostPainted: '',
    meshFailures: [],
    pixelRatio: 1,
    software: false,
    renderedFrames: 0,
    ghostSource: null,
    frameHooks: new Set<(now: number) => boolean>(),
    renderHooks: new Set<(now: number) => void>(),
    onFailure: null as ((reason: string) => void) | null,
    zonesShown: 0,
    started: 0,
    disposed: false,
    loads,
    jointValues: () => [],
    showZones() {
      view.zonesShown++;
    },
    load(url: string) {
      return new Promise<void>((resolve, reject) => loads.push({ url, resolve, reject }));
    },
    start() {
      view.started++;
    },
    invalidate() {},
    dispose() {
      view.disposed = true;
    },
  };
  return view;
}
type Fake = ReturnType<typeof fakeView>;

function setup() {
  const worker = fakeView('worker');
  const main = fakeView('main');
  const reasons: string[] = [];
  let mains = 0;
  const view = new FallbackSceneView(
    {
      worker: () => worker as unknown as FailingView,
      main: () => {
        mains++;
        return main as unknown as SceneView;
      },
    },
    (r) => reasons.push(r),
  );
  return { worker, main, reasons, view, mains: () => mains };
}

const settle = () => new Promise((r) => setTimeout(r, 0));

describe('FallbackSceneView', () => {
  it('draws in the worker while it works', async () => {
    const { worker, view, reasons, mains } = setup();
    expect(view.thread).toBe('worker');
    const loaded = view.load('arm.urdf', { names: [] } as never);
    worker.loads[0]!.resolve();
    await loaded;
    view.start();
    expect(worker.started).toBe(1);
    expect(reasons).toEqual([]);
    expect(mains()).toBe(0);
  });

  it('a worker error before the first frame moves everything to a main-thread view', async () => {
    const { worker, main, view, reasons } = setup();
    const hook = () => false;
    view.frameHooks.add(hook);
    const waypoint = new THREE.Mesh();
    view.world.add(waypoint);
    view.showZones(undefined);
    worker.camera.position.set(1, 2, 3);
    const loaded = view.load('arm.urdf', { names: [] } as never);
    worker.onFailure!('render worker: Uncaught Error: no WebGL');
    worker.loads[0]!.reject(new Error('render worker: Uncaught Error: no WebGL'));
    expect(view.thread).toBe('main');
    expect(reasons).toEqual(['render worker: Uncaught Error: no WebGL']);
    expect(fallbackChoice(reasons[0]!, true)).toEqual({
      thread: 'main',
      note: 'worker failed: render worker: Uncaught Error: no WebGL',
      pace: true,
    });
    expect(worker.disposed).toBe(true);
    expect(main.frameHooks.has(hook)).toBe(true);
    expect(waypoint.parent).toBe(main.world);
    expect(main.camera.position.toArray()).toEqual([1, 2, 3]);
    expect(main.zonesShown).toBe(1);
    // The robot is loaded again on the main thread; the caller's load settles with that one.
    expect(main.loads.map((l) => l.url)).toEqual(['arm.urdf']);
    let done = false;
    void loaded.then(() => (done = true));
    await settle();
    expect(done).toBe(false);
    main.loads[0]!.resolve();
    await settle();
    expect(done).toBe(true);
  });

  it('a model that fails to load in the worker is loaded on the main thread', async () => {
    const { worker, main, view, reasons } = setup();
    const loaded = view.load('arm.urdf', { names: [] } as never);
    worker.loads[0]!.reject(new Error('DOMParser is not defined'));
    await settle();
    expect(view.thread).toBe('main');
    expect(reasons[0]).toMatch(/model failed to load there: DOMParser is not defined/);
    main.loads[0]!.resolve();
    await loaded;
  });

  it('after the first frame a failure is not a fallback', async () => {
    const { worker, view, reasons, mains } = setup();
    const loaded = view.load('arm.urdf', { names: [] } as never);
    worker.loads[0]!.resolve();
    await loaded;
    view.start();
    worker.renderedFrames = 1;
    worker.onFailure?.('context lost');
    const next = view.load('other.urdf', { names: [] } as never);
    worker.loads[1]!.reject(new Error('404'));
    await expect(next).rejects.toThrow('404');
    expect(view.thread).toBe('worker');
    expect(reasons).toEqual([]);
    expect(mains()).toBe(0);
  });

  it('a worker that cannot be built gives a main-thread view at once, saying why', () => {
    const main = fakeView('main') as Fake;
    const reasons: string[] = [];
    const view = new FallbackSceneView(
      {
        worker: () => {
          throw new Error('module workers are not supported');
        },
        main: () => main as unknown as SceneView,
      },
      (r) => reasons.push(r),
    );
    expect(view.thread).toBe('main');
    expect(reasons).toEqual(['module workers are not supported']);
  });

  it('a worker failing after the model loaded and start(): the main view starts once loaded', async () => {
    const { worker, main, view } = setup();
    const loaded = view.load('arm.urdf', { names: [] } as never);
    worker.loads[0]!.resolve();
    await loaded;
    view.start();
    worker.onFailure!('render worker: WebGL context could not be created');
    expect(main.started).toBe(0);
    main.loads[0]!.resolve();
    await settle();
    expect(main.started).toBe(1);
  });
});
