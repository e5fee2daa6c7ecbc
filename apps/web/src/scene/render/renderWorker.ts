/**
 * The render worker: hosts the scene runtime (./sceneHost.ts, ./SceneRuntime.ts) on the
 * OffscreenCanvas the page hands over (./SceneClient.ts), so WebGL never runs on the page's main
 * thread and the emergency stop, MQTT and the panels never wait for a frame. Workers have no
 * DOMParser, which urdf-loader and three's ColladaLoader parse XML with: linkedom's (a small
 * standards-following DOM, its worker build) stands in, with its Document, Element and Node.
 * With software WebGL the frames are paced to a budget (`SOFTWARE_PACING`) unless the page asked
 * for every frame; no warm-up burst here: a slow frame in the worker holds up nothing on the
 * page, so the first frames are drawn at full resolution and the governor lowers it only once
 * things move. Messages: ./messages.ts.
 */
import {
  DOMParser as LinkedomParser,
  Document as LinkedomDocument,
  Element as LinkedomElement,
  Node as LinkedomNode,
} from 'linkedom/worker';
import { SOFTWARE_PACING } from '../FramePacer.ts';
import { hostScene, type ScenePort } from './sceneHost.ts';

const scope = self as unknown as ScenePort & {
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

hostScene(scope, { pacing: (software, pace) => (software && pace ? SOFTWARE_PACING : {}) });
