// The contract's JSON-schema validators, compiled when the site is built. Ajv turns a schema into
// code with `new Function` at run time, which the site's content-security policy (web/build/csp.ts)
// forbids; Ajv's standalone mode writes the same code into a module instead. In the build, the
// `ajv/dist/2020` that web/src/contract/validate.ts imports is this small stand-in: its compile()
// hands back the precompiled validator of the schema's $id. The dev server and the unit tests
// (no policy there) run the real Ajv on the same schemas with the same options.
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import Ajv2020 from 'ajv/dist/2020.js';
import standaloneCode from 'ajv/dist/standalone/index.js';
import type { Plugin } from 'vite';

/** The options web/src/contract/validate.ts gives Ajv; the stand-in refuses any others. */
export const VALIDATOR_OPTIONS = { allErrors: false, strict: false } as const;

const ID = '\0motion-futures:precompiled-ajv';

/** The stand-in module: every *.schema.json in `contractDir`, compiled, behind Ajv's compile(). */
export function precompiledAjvModule(contractDir: string): string {
  const files = readdirSync(contractDir).filter((f) => f.endsWith('.schema.json')).sort();
  const schemas = files.map((f) => JSON.parse(readFileSync(join(contractDir, f), 'utf8')) as { $id?: string });
  const ajv = new Ajv2020({ ...VALIDATOR_OPTIONS, code: { source: true, esm: true } });
  const exports: Record<string, string> = {};
  schemas.forEach((s, i) => {
    if (!s.$id) throw new Error(`${files[i]} has no $id, so validate.ts cannot be given its precompiled validator`);
    ajv.addSchema(s);
    exports[`v${i}`] = s.$id;
  });
  let code = standaloneCode(ajv, exports);
  // The generated code reaches Ajv's few run-time helpers (string length, deep equality) by
  // require(); a module imports them.
  const helpers = [...new Set([...code.matchAll(/require\("([^"]+)"\)/g)].map((m) => m[1]))];
  helpers.forEach((path, i) => { code = code.split(`require("${path}")`).join(`ajvHelper${i}`); });
  if (/\brequire\(/.test(code)) throw new Error('the precompiled validators still call require()');
  const byId = Object.entries(exports).map(([name, id]) => `${JSON.stringify(id)}: ${name}`).join(', ');
  return `${helpers.map((path, i) => `import * as ajvHelper${i} from ${JSON.stringify(path)};`).join('\n')}
${code}
const BY_ID = { ${byId} };
const OPTIONS = ${JSON.stringify(VALIDATOR_OPTIONS)};
export default class PrecompiledAjv {
  constructor(options = {}) {
    const key = (o) => JSON.stringify(Object.entries(o).sort());
    if (key(options) !== key(OPTIONS)) {
      throw new Error('the contract validators were compiled with Ajv options ' + JSON.stringify(OPTIONS)
        + ', not ' + JSON.stringify(options) + ': change VALIDATOR_OPTIONS in web/build/precompiled-validators.ts to match');
    }
  }
  addSchema() { return this; }
  compile(schema) {
    const validate = BY_ID[schema && schema.$id];
    if (!validate) throw new Error('no precompiled validator for the schema ' + (schema && schema.$id));
    return validate;
  }
}
`;
}

export function precompiledValidators(contractDir: string): Plugin {
  return {
    name: 'motion-futures:precompiled-validators',
    apply: 'build',
    enforce: 'pre',
    resolveId(source) {
      return source === 'ajv/dist/2020' ? ID : null;
    },
    load(id) {
      return id === ID ? precompiledAjvModule(contractDir) : null;
    },
  };
}
