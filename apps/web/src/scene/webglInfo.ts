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

/** Whether WebGL in this page is rasterized on the CPU (false when unknown or no WebGL). */
export function isSoftwareWebGL(): boolean {
  try {
    const gl = document.createElement('canvas').getContext('webgl');
    if (!gl) return false;
    const ext = gl.getExtension('WEBGL_debug_renderer_info');
    const name = String(gl.getParameter(ext ? ext.UNMASKED_RENDERER_WEBGL : gl.RENDERER));
    gl.getExtension('WEBGL_lose_context')?.loseContext();
    return isSoftwareRenderer(name);
  } catch {
    return false;
  }
}
