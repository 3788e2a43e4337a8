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

export function requireWebGL2(): void {
  const support = webglSupport();
  if (support === 'webgl2') return;
  throw new WebGLUnavailableError(support === 'webgl'
    ? 'This browser offers WebGL 1 only; the 3D viewer needs WebGL 2.'
    : 'WebGL is not available in this browser (it may be turned off, or the graphics driver is blocked), so the 3D viewer cannot be shown.');
}
