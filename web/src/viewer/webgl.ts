// Probe for WebGL 2 before three.js is asked for a renderer (three.js needs WebGL 2).

export class WebGLUnavailableError extends Error {
  constructor(message: string) {
    super(message);
    this.name = 'WebGLUnavailableError';
  }
}

export function webglSupport(): 'webgl2' | 'webgl' | null {
  try {
    const canvas = document.createElement('canvas');
    const gl2 = canvas.getContext('webgl2');
    const gl = gl2 ?? canvas.getContext('webgl');
    // Release the probe's context now: browsers cap live contexts.
    gl?.getExtension('WEBGL_lose_context')?.loseContext();
    return gl2 ? 'webgl2' : gl ? 'webgl' : null;
  } catch {
    return null;
  }
}

const SOFTWARE = /swiftshader|llvmpipe|softpipe|software/i;

/**
 * Whether WebGL 2 here is drawn by the CPU (SwiftShader, llvmpipe: a machine without a usable GPU).
 * The browser says so by refusing a context that asks to fail on a major performance caveat; the
 * renderer's name is the fallback where that flag is not honoured.
 */
export function softwareWebGL(): boolean {
  try {
    const fast = document.createElement('canvas').getContext('webgl2', { failIfMajorPerformanceCaveat: true });
    if (!fast) return true;
    const info = fast.getExtension('WEBGL_debug_renderer_info');
    const name = String(info ? fast.getParameter(info.UNMASKED_RENDERER_WEBGL) : fast.getParameter(fast.RENDERER));
    fast.getExtension('WEBGL_lose_context')?.loseContext();
    return SOFTWARE.test(name);
  } catch {
    return false;
  }
}

export function requireWebGL2(): void {
  const support = webglSupport();
  if (support === 'webgl2') return;
  throw new WebGLUnavailableError(support === 'webgl'
    ? 'This browser offers WebGL 1 only; the 3D viewer needs WebGL 2.'
    : 'WebGL is not available in this browser (it may be turned off, or the graphics driver is blocked), so the 3D viewer cannot be shown.');
}
