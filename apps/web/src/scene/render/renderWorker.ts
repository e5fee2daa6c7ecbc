/**
 * The render worker: draws the 3D view on the OffscreenCanvas the page hands over
 * (./WorkerHost.ts), so WebGL never runs on the page's main thread and the emergency stop,
 * MQTT and the panels never wait for a frame. Workers have no DOMParser, which urdf-loader and
 * three's ColladaLoader parse XML with: linkedom's (a small standards-following DOM, its
 * worker build) stands in, with its Document, Element and Node. Messages: ./messages.ts.
 */
import {
  DOMParser as LinkedomParser,
  Document as LinkedomDocument,
  Element as LinkedomElement,
  Node as LinkedomNode,
} from 'linkedom/worker';
import type { FromWorker, ToWorker } from './messages.ts';
import { WorkerScene } from './WorkerScene.ts';
import { webglRenderer, isSoftwareRenderer } from '../webglInfo.ts';

const scope = self as unknown as {
  postMessage(m: FromWorker): void;
  onmessage: ((e: MessageEvent<ToWorker>) => void) | null;
  DOMParser?: unknown;
  Document?: unknown;
  Element?: unknown;
  Node?: unknown;
};
// urdf-loader also asks `instanceof Document / Element`, ColladaLoader `Node.TEXT_NODE`.
scope.DOMParser ??= LinkedomParser;
scope.Document ??= LinkedomDocument;
scope.Element ??= LinkedomElement;
scope.Node ??= LinkedomNode;

const post = (m: FromWorker): void => scope.postMessage(m);
let scene: WorkerScene | null = null;

scope.onmessage = (e) => {
  const m = e.data;
  try {
    switch (m.type) {
      case 'init': {
        const renderer = webglRenderer(() => new OffscreenCanvas(1, 1));
        const software = isSoftwareRenderer(renderer);
        scene = new WorkerScene(m.canvas, software, m.dpr, post, software && m.pace);
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
