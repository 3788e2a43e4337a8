// `node bench/run.mjs PLAN.json OUT.json`: runs bench/browser.ts (TypeScript, through vite's module
// runner, so bench/ shares tests/e2e's helpers without a build step). export/bench calls this.
import { runnerImport } from 'vite';

const [plan, out] = process.argv.slice(2);
if (!plan || !out) {
  console.error('usage: node bench/run.mjs PLAN.json OUT.json (written by python -m export bench)');
  process.exit(2);
}
const { module } = await runnerImport(new URL('./browser.ts', import.meta.url).pathname, { configFile: false, logLevel: 'warn' });
await module.main(plan, out);
