/**
 * The WebGL renderer as the 3D view uses it, on the page's canvas or the render worker's
 * OffscreenCanvas: shadows drawn only when asked (`shadowMap.autoUpdate` off: the loop sets
 * `needsUpdate` when a shadow caster moved), sRGB output, and no MSAA on software WebGL
 * (SwiftShader, llvmpipe pay for every multisampled pixel on the CPU; the resolution governor's
 * scaling smooths edges there).
 */
import * as THREE from 'three';

export function createRenderer(
  software: boolean,
  canvas?: HTMLCanvasElement | OffscreenCanvas,
): THREE.WebGLRenderer {
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: !software });
  renderer.shadowMap.enabled = true;
  renderer.shadowMap.type = THREE.PCFShadowMap;
  renderer.shadowMap.autoUpdate = false;
  renderer.outputColorSpace = THREE.SRGBColorSpace;
  return renderer;
}
