/**
 * URDF as XML: the one place a URDF's text is parsed (`@xmldom/xmldom`'s DOMParser, the same
 * W3C API the page's urdf-loader uses, in Node and in the page's bundle alike). Only the
 * `<robot>` element's own `<link>` and `<joint>` children describe the robot; `<joint>`s inside
 * `<ros2_control>`, `<transmission>` or `<gazebo>` are references to those, never joints.
 */
import { DOMParser, XMLSerializer, type Document, type Element } from '@xmldom/xmldom';

export type UrdfDocument =
  { ok: true; doc: Document; robot: Element } | { ok: false; errors: string[] };

/** Parses a URDF's text; not well-formed XML or a root other than `<robot>` is an error. */
export function parseUrdfXml(xml: string): UrdfDocument {
  const errors: string[] = [];
  let doc: Document;
  try {
    doc = new DOMParser({
      onError: (level, message) => {
        if (level !== 'warning') errors.push(`not well-formed XML: ${firstLine(message)}`);
      },
    }).parseFromString(xml, 'text/xml');
  } catch (err) {
    if (errors.length === 0) errors.push(`not well-formed XML: ${firstLine(String(err))}`);
    return { ok: false, errors };
  }
  if (errors.length > 0) return { ok: false, errors };
  const robot = doc.documentElement;
  if (!robot || robot.localName !== 'robot') return { ok: false, errors: ['no <robot> element'] };
  return { ok: true, doc, robot };
}

/** The XML text of a parsed URDF (after edits to its elements). */
export function serializeUrdf(doc: Document): string {
  return new XMLSerializer().serializeToString(doc);
}

/** `el`'s own child elements named `tag` (not deeper ones), in document order. */
export function childElements(el: Element, tag: string): Element[] {
  const out: Element[] = [];
  for (let n = el.firstChild; n; n = n.nextSibling)
    if (n.nodeType === n.ELEMENT_NODE && (n as Element).localName === tag) out.push(n as Element);
  return out;
}

/** `el`'s first own child element named `tag`, or undefined. */
export const childElement = (el: Element, tag: string): Element | undefined =>
  childElements(el, tag)[0];

/** An attribute's value, or undefined when the element or the attribute is absent. */
export const attribute = (el: Element | undefined, name: string): string | undefined =>
  el?.hasAttribute(name) ? (el.getAttribute(name) ?? '') : undefined;

const firstLine = (s: string): string => s.split('\n')[0]!.trim();
