// Probe for WebGL 2 before three.js is asked for a renderer (three.js needs WebGL 2), and for whether
// the CPU draws it.

export class WebGLUnavailableError extends Error {
  constructor(message: string) {
    super(message);
    this.name = 'WebGLUnavailableError';
  }
}

const SOFTWARE = /swiftshader|llvmpipe|softpipe|software/i;

/**
 * What WebGL this browser offers, and whether its WebGL 2 is drawn by the CPU (SwiftShader, llvmpipe:
 * a machine without a usable GPU). A browser says so by refusing a context that must not have a major
 * performance caveat; the renderer's name is the fallback where that flag is not honoured. One probe
 * context in the usual case, released at once: browsers cap live contexts.
 */
function probeWebGL(): { support: 'webgl2' | 'webgl' | null; software: boolean } {
  try {
    const fast = document.createElement('canvas').getContext('webgl2', { failIfMajorPerformanceCaveat: true });
    if (fast) {
      const info = fast.getExtension('WEBGL_debug_renderer_info');
      const name = String(info ? fast.getParameter(info.UNMASKED_RENDERER_WEBGL) : fast.getParameter(fast.RENDERER));
      fast.getExtension('WEBGL_lose_context')?.loseContext();
      return { support: 'webgl2', software: SOFTWARE.test(name) };
    }
    const canvas = document.createElement('canvas');
    const gl2 = canvas.getContext('webgl2');
    const gl = gl2 ?? canvas.getContext('webgl');
    gl?.getExtension('WEBGL_lose_context')?.loseContext();
    return { support: gl2 ? 'webgl2' : gl ? 'webgl' : null, software: true };
  } catch {
    return { support: null, software: false };
  }
}

/** Throws WebGLUnavailableError without WebGL 2; says whether the CPU draws it. */
export function requireWebGL2(): { software: boolean } {
  const { support, software } = probeWebGL();
  if (support === 'webgl2') return { software };
  throw new WebGLUnavailableError(support === 'webgl'
    ? 'This browser offers WebGL 1 only; the 3D viewer needs WebGL 2.'
    : 'WebGL is not available in this browser (it may be turned off, or the graphics driver is blocked), so the 3D viewer cannot be shown.');
}
