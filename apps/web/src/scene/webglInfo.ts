/**
 * What kind of WebGL the page got. A throwaway context is asked for its renderer string (the
 * unmasked one when the browser allows) and released at once.
 */

/** Renderer strings of CPU rasterizers: Chrome's SwiftShader, Mesa's llvmpipe / softpipe. */
const SOFTWARE = /swiftshader|llvmpipe|softpipe|software/i;

/** Whether a renderer string names a software rasterizer. Pure. */
export function isSoftwareRenderer(name: string): boolean {
  return SOFTWARE.test(name);
}

/**
 * Whether WebGL in this page is rasterized on the CPU (false when unknown or no WebGL).
 * `canvas` makes the throwaway canvas (an OffscreenCanvas in the render worker).
 */
export function isSoftwareWebGL(
  canvas: () => HTMLCanvasElement | OffscreenCanvas = () => document.createElement('canvas'),
): boolean {
  return isSoftwareRenderer(webglRenderer(canvas));
}

/** WebGL's renderer string (unmasked when allowed), '' when unknown or no WebGL. */
export function webglRenderer(
  canvas: () => HTMLCanvasElement | OffscreenCanvas = () => document.createElement('canvas'),
): string {
  try {
    const gl = canvas().getContext('webgl') as WebGLRenderingContext | null;
    if (!gl) return '';
    const ext = gl.getExtension('WEBGL_debug_renderer_info');
    const name = String(gl.getParameter(ext ? ext.UNMASKED_RENDERER_WEBGL : gl.RENDERER));
    gl.getExtension('WEBGL_lose_context')?.loseContext();
    return name;
  } catch {
    return '';
  }
}
