/**
 * A URDF parsed by urdf-loader in node, as the page would (joints and links, no meshes loaded):
 * urdf-loader parses with the browser's DOMParser, for which happy-dom's stands in.
 */
import { Window } from 'happy-dom';
import URDFLoader, { type URDFRobot } from 'urdf-loader';

export function parseUrdf(text: string): URDFRobot {
  const win = new Window();
  Object.assign(globalThis, {
    DOMParser: win.DOMParser,
    Document: win.Document,
    Element: win.Element,
  });
  const loader = new URDFLoader();
  loader.parseVisual = false;
  return loader.parse(text);
}
