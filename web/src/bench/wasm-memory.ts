// Keeps a handle on every WebAssembly.Memory that onnxruntime instantiates in this worker, so the
// benchmark and the memory test can read how much wasm memory the worker holds. Installed only
// when the page asks for instrumentation (PredictorClient's `instrument`), before onnxruntime loads.
type Instantiated = WebAssembly.WebAssemblyInstantiatedSource | WebAssembly.Instance;

declare global {
  // eslint-disable-next-line no-var
  var __mfWasmMemories: WebAssembly.Memory[] | undefined;
}

function keep(imports: unknown, result: Instantiated): void {
  const found = globalThis.__mfWasmMemories ??= [];
  const instance = result instanceof WebAssembly.Instance ? result : result.instance;
  const candidates: unknown[] = [...Object.values(instance.exports)];
  for (const ns of Object.values((imports ?? {}) as Record<string, Record<string, unknown>>)) {
    if (ns && typeof ns === 'object') candidates.push(...Object.values(ns));
  }
  for (const c of candidates) if (c instanceof WebAssembly.Memory && !found.includes(c)) found.push(c);
}

export function captureWasmMemory(): void {
  if (globalThis.__mfWasmMemories) return;
  globalThis.__mfWasmMemories = [];
  const wasm = WebAssembly as unknown as Record<string, (...args: unknown[]) => Promise<Instantiated>>;
  for (const name of ['instantiate', 'instantiateStreaming']) {
    const original = wasm[name];
    if (typeof original !== 'function') continue;
    wasm[name] = async (...args: unknown[]) => {
      const result = await original.apply(WebAssembly, args);
      keep(args[1], result);
      return result;
    };
  }
}

/** Bytes of wasm memory the worker holds now (null before onnxruntime instantiated its module). */
export function wasmMemoryBytes(): number | null {
  const found = globalThis.__mfWasmMemories;
  return found?.length ? found.reduce((s, m) => s + m.buffer.byteLength, 0) : null;
}
