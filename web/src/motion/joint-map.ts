// Joint maps (contract/joint-maps/*.json): which source point each project joint follows.
// Twin of the map half of export/data/retarget.py; both read the same JSON files.
import cmuAsf from '../../../contract/joint-maps/cmu-asf.json';
import cmuBvh from '../../../contract/joint-maps/cmu-bvh.json';
import daz from '../../../contract/joint-maps/daz.json';
import order from '../../../contract/joint-maps/order.json';
import smpl from '../../../contract/joint-maps/smpl.json';

export type Alternative = string | null;

/** A joint map file, or a user's override of one (every field optional). */
export interface JointMapDoc {
  format?: string;
  version?: number;
  name?: string;
  about?: string;
  extends?: string;
  up?: 'y' | 'z';
  joints?: Record<string, Alternative[]>;
  orders?: Record<string, string[]>;
}

export interface JointMap {
  name: string;
  up: 'y' | 'z';
  joints: Record<string, Alternative[]>;
  orders: Record<string, string[]>;
}

export const BUILTIN_MAPS: Record<string, JointMapDoc> = {
  'cmu-asf': cmuAsf as JointMapDoc,
  'cmu-bvh': cmuBvh as JointMapDoc,
  daz: daz as JointMapDoc,
  smpl: smpl as JointMapDoc,
};

/** The built-in maps a dropped BVH is tried with, in this order: the first whose joint names the file
 *  has wins (cmu-bvh first, so CMU-style files read as before; then Daz-style skeletons). The list is
 *  contract/joint-maps/order.json's, which the command line reads too (retarget.py tried_maps). */
export const BVH_MAPS: readonly string[] = order.bvh;
/** The same for an ASF/AMC pair. */
export const ASF_AMC_MAPS: readonly string[] = order['asf-amc'];

/** Joints whose point may be derived when the source lacks it (alternative null). */
export const DERIVABLE = ['head', 'right_toe', 'left_toe'];
const KEYS = ['format', 'version', 'name', 'about', 'extends', 'up', 'joints', 'orders'];

export class JointMapError extends Error {
  constructor(message: string) {
    super(message);
    this.name = 'JointMapError';
  }
}

function isObject(v: unknown): v is Record<string, unknown> {
  return typeof v === 'object' && v !== null && !Array.isArray(v);
}

function check(doc: unknown, where: string, projectJoints: readonly string[]): JointMapDoc {
  if (!isObject(doc)) throw new JointMapError(`${where}: a joint map is a JSON object`);
  const unknown = Object.keys(doc).filter((k) => !KEYS.includes(k)).sort();
  if (unknown.length) throw new JointMapError(`${where}: unknown field '${unknown[0]}' (a joint map has ${KEYS.join(', ')})`);
  for (const key of ['joints', 'orders']) {
    if (key in doc && !isObject(doc[key])) throw new JointMapError(`${where}: field ${key}: must be a JSON object`);
  }
  const up = doc.up ?? 'y';
  if (up !== 'y' && up !== 'z') throw new JointMapError(`${where}: field up: must be "y" or "z", got ${JSON.stringify(up)}`);
  for (const [joint, alts] of Object.entries((doc.joints ?? {}) as Record<string, unknown>)) {
    if (!projectJoints.includes(joint)) {
      throw new JointMapError(`${where}: field joints/${joint}: not a project joint (${projectJoints.join(', ')})`);
    }
    if (!Array.isArray(alts) || !alts.length || !alts.every((a) => a === null || (typeof a === 'string' && a.length > 0))) {
      throw new JointMapError(`${where}: field joints/${joint}: must be a non-empty list of source names or null`);
    }
    if (alts.includes(null) && !DERIVABLE.includes(joint)) {
      throw new JointMapError(`${where}: field joints/${joint}: only ${DERIVABLE.join(', ')} can be derived (null)`);
    }
  }
  for (const [count, names] of Object.entries((doc.orders ?? {}) as Record<string, unknown>)) {
    if (!/^\d+$/.test(count) || !Array.isArray(names) || names.length !== Number(count)) {
      throw new JointMapError(`${where}: field orders/${count}: must list exactly ${count} joint names`);
    }
  }
  return doc as JointMapDoc;
}

function builtin(name: unknown): JointMapDoc {
  if (typeof name !== 'string' || !(name in BUILTIN_MAPS)) {
    throw new JointMapError(`no joint map named ${JSON.stringify(name)} (built in: ${Object.keys(BUILTIN_MAPS).sort().join(', ')})`);
  }
  return BUILTIN_MAPS[name];
}

/** A built-in map with a user's override on top: `joints` merge per project joint, `up` and
 *  `orders` entries replace; `extends` in the override names another built-in base. */
export function loadJointMap(
  base: string, projectJoints: readonly string[], override?: unknown, where = 'joint map',
): JointMap {
  let doc = builtin(base);
  if (override !== undefined && override !== null && isObject(override) && override.extends !== undefined) {
    if (typeof override.extends !== 'string') throw new JointMapError(`${where}: field extends: the name of a built-in joint map`);
    doc = builtin(override.extends);
  }
  check(doc, doc.name ?? 'joint map', projectJoints);
  const out: JointMap = { name: doc.name ?? 'custom', up: doc.up ?? 'y', joints: { ...doc.joints }, orders: { ...doc.orders } };
  if (override !== undefined && override !== null) {
    const o = check(override, where, projectJoints);
    out.up = o.up ?? out.up;
    Object.assign(out.joints, o.joints ?? {});
    Object.assign(out.orders, o.orders ?? {});
    out.name = `${out.name} + ${where}`;
  }
  const missing = projectJoints.filter((j) => !(j in out.joints));
  if (missing.length) throw new JointMapError(`${where}: no entry for project joints ${missing.join(', ')}`);
  return out;
}

/** Parse a user's joint map file; errors name the file. */
export function parseJointMap(text: string, where: string): unknown {
  try {
    return JSON.parse(text);
  } catch (err) {
    throw new JointMapError(`${where}: not a readable joint map JSON (${(err as Error).message})`);
  }
}
