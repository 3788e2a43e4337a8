import { describe, expect, it } from 'vitest';
import { readFileSync, readdirSync } from 'node:fs';
import { ContractError, parseJson, validate } from '../../web/src/contract/validate';
import { motionFromDoc } from '../../web/src/motion/clip';

const clipsDir = new URL('../../public/clips/', import.meta.url);
const read = (name: string) => readFileSync(new URL(name, clipsDir), 'utf8');

describe('contract validation in TypeScript', () => {
  it('accepts every committed clip and the index', () => {
    const index = validate(parseJson(read('index.json'), 'index.json'), 'clip-index', 'index.json');
    const files = readdirSync(clipsDir).filter((f) => f.endsWith('.json') && f !== 'index.json');
    expect(files.sort()).toEqual(index.clips.map((c) => c.file).sort());
    for (const f of files) {
      const doc = validate(parseJson(read(f), f), 'clip', f);
      const m = motionFromDoc(doc);
      expect(m.positions.length).toBe(m.frames * m.joints * 3);
    }
  });

  it('a clip with NaN names the file and the problem', () => {
    const raw = read('deepmimic_walk.json');
    const at = raw.indexOf('"positions": [\n[[') + '"positions": [\n[['.length;
    const text = `${raw.slice(0, at)}NaN${raw.slice(raw.indexOf(',', at))}`;
    expect(() => parseJson(text, 'clips/walk.json')).toThrow(ContractError);
    expect(() => parseJson(text, 'clips/walk.json')).toThrow(/clips\/walk\.json: not valid JSON \(NaN/);
  });

  it('a clip with a null coordinate names the field', () => {
    const doc = JSON.parse(read('deepmimic_walk.json'));
    doc.positions[3][5][1] = null;
    expect(() => validate(doc, 'clip', 'clips/walk.json')).toThrow(/clips\/walk\.json: field positions\/3\/5\/1: must be number/);
  });

  it('a clip whose frame has the wrong joint count names the frame', () => {
    const doc = JSON.parse(read('deepmimic_walk.json'));
    doc.positions[7].pop();
    expect(() => validate(doc, 'clip', 'walk.json')).toThrow(/walk\.json: field positions\/7: 17 joints, the skeleton has 18/);
  });

  it('a manifest missing a field names the file and the field', () => {
    const manifest = {
      format: 'motion-futures/manifest', version: 1, fps: 30,
      skeleton: { joints: ['root', 'chest'], parents: [-1, 0] }, actions: ['walk'], data_hash: 'sha256:' + '0'.repeat(64),
      models: [{ id: 'm', method: 'regression', label: 'M', hash: 'sha256:' + '0'.repeat(64),
        graphs: { decoder: { file: 'm.onnx', inputs: [{ name: 'history', shape: ['batch', 10, 18, 3], dtype: 'float32' }],
          outputs: [{ name: 'future', shape: ['batch', 30, 18, 3], dtype: 'float32' }] } },
        params: { history_frames: 10 }, controls: [] }],
    };
    expect(() => validate(manifest, 'manifest', 'models/manifest.json'))
      .toThrow(/models\/manifest\.json: field models\/0\/params\/future_frames: is missing/);
  });

  it('the served manifest stores the shared speed envelope once, and every model reads it back', () => {
    const text = readFileSync(new URL('../../public/models/manifest.json', import.meta.url), 'utf8');
    const raw = JSON.parse(text);
    const shared = raw.speed_envelope as Record<string, unknown>;
    expect(Object.keys(shared)).toContain('tempo_poses');
    for (const m of raw.models) expect(Object.keys(m.params.envelope ?? {})).not.toContain('tempo_poses');
    const doc = validate(parseJson(text, 'manifest.json'), 'manifest', 'manifest.json');
    expect('speed_envelope' in doc).toBe(false);
    const withEnv = doc.models.filter((m) => 'envelope' in m.params);
    expect(withEnv.length).toBe(raw.models.length);
    for (const m of withEnv) {
      const env = (m.params as { envelope?: Record<string, unknown> }).envelope ?? {};
      for (const [q, v] of Object.entries(shared)) expect(env[q]).toEqual(v);
      // the model's own quantities are kept beside the shared ones
      const own = raw.models.find((r: { id: string }) => r.id === m.id).params.envelope;
      for (const [q, v] of Object.entries(own)) expect(env[q]).toEqual(v);
    }
  });
});
