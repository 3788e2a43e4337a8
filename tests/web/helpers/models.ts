// Node-side access to the committed models: the same OrtRunner and predictors the worker uses,
// with onnxruntime-web's Node build and files read from public/models.
import { readFileSync } from 'node:fs';
import * as ort from 'onnxruntime-web';
import { parseJson, validate } from '../../../web/src/contract/validate';
import type { Manifest } from '../../../web/src/contract/types';
import { createCheckedPredictor } from '../../../web/src/predictor/history';
import { OrtRunner, type OrtModule } from '../../../web/src/predictor/ort-runner';
import type { Predictor } from '../../../web/src/predictor/types';

const modelsDir = new URL('../../../public/models/', import.meta.url);
ort.env.wasm.numThreads = 1;
ort.env.logLevel = 'error';

export function loadManifest(): Manifest {
  return validate(parseJson(readFileSync(new URL('manifest.json', modelsDir), 'utf8'), 'manifest.json'), 'manifest', 'manifest.json');
}

export function nodePredictor(manifest: Manifest, id: string): Predictor {
  const entry = manifest.models.find((m) => m.id === id);
  if (!entry) throw new Error(`no model ${id}`);
  const load = async (file: string) => new Uint8Array(readFileSync(new URL(file, modelsDir)));
  const runner = new OrtRunner(ort as unknown as OrtModule, entry, load);
  return createCheckedPredictor({ entry, skeleton: manifest.skeleton, actions: manifest.actions, fps: manifest.fps, runner, loadFile: load });
}
