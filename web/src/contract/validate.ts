// Load-time validation of contract files against the shared JSON schemas in contract/.
// Every error names the file and the field, so a broken file never becomes a blank page.
import Ajv2020, { type ErrorObject, type ValidateFunction } from 'ajv/dist/2020';
import defsSchema from '../../../contract/defs.schema.json';
import clipSchema from '../../../contract/clip.schema.json';
import clipIndexSchema from '../../../contract/clip-index.schema.json';
import manifestSchema from '../../../contract/manifest.schema.json';
import type { ClipDoc, ClipIndex, Manifest, Skeleton } from './types';

export class ContractError extends Error {
  constructor(message: string) {
    super(message);
    this.name = 'ContractError';
  }
}

type SchemaName = 'clip' | 'clip-index' | 'manifest';
interface Docs { clip: ClipDoc; 'clip-index': ClipIndex; manifest: Manifest }

let validators: Record<SchemaName, ValidateFunction> | null = null;

function compiled(): Record<SchemaName, ValidateFunction> {
  if (!validators) {
    const ajv = new Ajv2020({ allErrors: false, strict: false });
    ajv.addSchema(defsSchema);
    validators = {
      clip: ajv.compile(clipSchema),
      'clip-index': ajv.compile(clipIndexSchema),
      manifest: ajv.compile(manifestSchema),
    };
  }
  return validators;
}

function field(e: ErrorObject): string {
  const path = e.instancePath.replace(/^\//, '');
  const extra = e.keyword === 'required' ? `/${(e.params as { missingProperty: string }).missingProperty}` : '';
  return (path + extra).replace(/^\//, '') || '(top level)';
}

function describe(e: ErrorObject): string {
  if (e.keyword === 'required') return 'is missing';
  if (e.keyword === 'additionalProperties') {
    return `has an unknown field "${(e.params as { additionalProperty: string }).additionalProperty}"`;
  }
  return e.message ?? e.keyword;
}

function checkSkeleton(s: Skeleton, where: string): void {
  if (s.parents.length !== s.joints.length) {
    throw new ContractError(`${where}: field skeleton/parents: ${s.parents.length} parents for ${s.joints.length} joints`);
  }
  s.parents.forEach((p, j) => {
    if (p >= j || (p < 0 && j !== 0)) {
      throw new ContractError(`${where}: field skeleton/parents/${j}: parent ${p} must precede joint ${j} (only joint 0 is the root)`);
    }
  });
}

function checkClip(doc: ClipDoc, where: string): void {
  const joints = doc.skeleton.joints.length;
  doc.positions.forEach((frame, f) => {
    if (frame.length !== joints) {
      throw new ContractError(`${where}: field positions/${f}: ${frame.length} joints, the skeleton has ${joints}`);
    }
  });
  const frames = doc.positions.length;
  for (const key of ['train', 'test'] as const) {
    doc.split[key].forEach(([a, b], i) => {
      if (!(a >= 0 && a < b && b <= frames)) {
        throw new ContractError(`${where}: field split/${key}/${i}: range [${a}, ${b}) is empty or outside 0..${frames}`);
      }
    });
  }
}

/** Validate a parsed document; throws ContractError naming `where` and the field. */
export function validate<S extends SchemaName>(doc: unknown, schema: S, where: string): Docs[S] {
  const v = compiled()[schema];
  if (!v(doc)) {
    const e = v.errors![0];
    throw new ContractError(`${where}: field ${field(e)}: ${describe(e)}`);
  }
  const typed = doc as Docs[S];
  checkSkeleton((typed as { skeleton: Skeleton }).skeleton, where);
  if (schema === 'clip') checkClip(typed as ClipDoc, where);
  if (schema === 'manifest') return expandSpeedEnvelope(typed as Manifest) as Docs[S];
  return typed;
}

/** The manifest as its models use it (twin of expand_speed_envelope in export/manifest.py): the file stores
 *  the speed envelope every model shares once, at its top level; each model's envelope gets it back. */
function expandSpeedEnvelope(doc: Manifest): Manifest {
  const shared = doc.speed_envelope;
  if (!shared) return doc;
  const { speed_envelope: _, ...rest } = doc;
  const models = doc.models.map((m) => {
    const env = (m.params as { envelope?: Record<string, unknown> }).envelope;
    return env ? { ...m, params: { ...m.params, envelope: { ...env, ...shared } } } : m;
  });
  return { ...rest, models };
}

/** Parse JSON text; NaN, null positions and syntax errors become a ContractError naming the file. */
export function parseJson(text: string, where: string): unknown {
  try {
    return JSON.parse(text);
  } catch (err) {
    const hint = /\bNaN\b|\bInfinity\b/.test(text) ? ' (NaN and Infinity are not numbers JSON allows)' : '';
    throw new ContractError(`${where}: not valid JSON${hint}: ${(err as Error).message}`);
  }
}

/** Fetch, parse and validate one contract file. */
export async function fetchContract<S extends SchemaName>(url: string, schema: S, fetcher: typeof fetch = fetch): Promise<Docs[S]> {
  let res: Response;
  try {
    res = await fetcher(url);
  } catch (err) {
    throw new ContractError(`${url}: could not be loaded (${(err as Error).message})`);
  }
  if (!res.ok) throw new ContractError(`${url}: could not be loaded (HTTP ${res.status})`);
  return validate(parseJson(await res.text(), url), schema, url);
}
