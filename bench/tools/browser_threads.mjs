// Bench: one remesh in headless Chromium on a cross-origin isolated page, the threaded WebAssembly
// build on N threads against the single-threaded build (what a page without the headers runs).
//   node bench/tools/browser_threads.mjs [model=fandisk.off] [edgeLengthRel=0.004] [pairs=5] [threads=2]
// Interleaved pairs whose order alternates, the page's defaults (the report's distance included),
// after one warm-up call each; prints the times, the median of the pairs' ratios, whether every
// run gave the same bytes, and the machine's load. Needs dist/ (scripts/build.sh).
import { readFile, mkdtemp, rm } from 'node:fs/promises';
import { createServer } from 'node:http';
import { cpus, loadavg, tmpdir } from 'node:os';
import { extname, join, normalize } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const [model = 'fandisk.off', rel = '0.004', pairs = '5', threads = '2'] = process.argv.slice(2);
const root = fileURLToPath(new URL('../../', import.meta.url));
const data = join(root, '..', 'shared', 'data');
const page = `<!doctype html><script type="module">
import { createRemesher } from '/dist/browser.js';
window.run = async (model, rel, pairs, threads) => {
  const bytes = new Uint8Array(await (await fetch('/data/' + model)).arrayBuffer());
  const single = createRemesher({ init: { threads: 1 } }), threaded = createRemesher({ init: { threads } });
  const mesh = await single.readMesh(bytes, { fileName: model });
  const once = async (r) => {
    const t0 = performance.now();
    const res = await r.remesh(mesh, { targetEdgeLengthRel: rel });
    const ms = performance.now() - t0;
    const off = new Uint8Array(await crypto.subtle.digest('SHA-256', await r.writeMesh(res.mesh, 'off')));
    return { ms, sha: off.join(',') };
  };
  await once(single);
  await once(threaded);
  const rows = [];
  for (let k = 0; k < pairs; ++k) {
    let s, t;
    if (k % 2) (t = await once(threaded)), (s = await once(single));
    else (s = await once(single)), (t = await once(threaded));
    rows.push({ single: s, threaded: t });
  }
  return { isolated: crossOriginIsolated, threads: await threaded.threads(), rows };
};
</script>`;

const types = { '.js': 'text/javascript', '.mjs': 'text/javascript', '.wasm': 'application/wasm' };
const server = createServer(async (req, res) => {
  const h = { 'cross-origin-opener-policy': 'same-origin', 'cross-origin-embedder-policy': 'require-corp' };
  const path = decodeURIComponent(new URL(req.url ?? '/', 'http://x').pathname);
  if (path === '/') return void res.writeHead(200, { ...h, 'content-type': 'text/html' }).end(page);
  if (path === '/favicon.ico') return void res.writeHead(204).end();
  const [base, rest] = path.startsWith('/data/') ? [data, path.slice(6)] : [root, path];
  const file = normalize(join(base, rest));
  try {
    if (!file.startsWith(base)) throw new Error('outside');
    const body = await readFile(file);
    res.writeHead(200, { ...h, 'content-type': types[extname(file)] ?? 'application/octet-stream' }).end(body);
  } catch {
    res.writeHead(404).end();
  }
});
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
const profile = await mkdtemp(join(tmpdir(), 'conformesh-bench-'));
const context = await chromium.launchPersistentContext(profile, {
  executablePath: '/usr/bin/chromium',
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--no-first-run', '--disable-background-networking'],
});
try {
  const tab = await context.newPage();
  tab.on('pageerror', (e) => console.error('page error:', e.message));
  tab.on('console', (m) => m.type() === 'error' && console.error('page:', m.text()));
  await tab.goto(`http://127.0.0.1:${server.address().port}/`);
  await tab.waitForFunction(() => 'run' in window);
  const load = loadavg()[0];
  const r = await tab.evaluate(([m, e, p, t]) => window.run(m, e, p, t), [model, Number(rel), Number(pairs), Number(threads)]);
  const ratios = r.rows.map((x) => x.threaded.ms / x.single.ms).sort((a, b) => a - b);
  const median = ratios.length % 2 ? ratios[(ratios.length - 1) / 2] : (ratios[ratios.length / 2 - 1] + ratios[ratios.length / 2]) / 2;
  const same = r.rows.every((x) => x.single.sha === r.rows[0].single.sha && x.threaded.sha === x.single.sha);
  console.log(`${model} at ${rel} in Chromium, cross-origin isolated: ${r.isolated}; threaded build on ${r.threads} threads`);
  console.log(`${cpus().length} cores, load ${load.toFixed(2)} before, ${loadavg()[0].toFixed(2)} after`);
  console.log('| pair | single-threaded ms | threaded ms | ratio |\n| --- | --- | --- | --- |');
  r.rows.forEach((x, k) => console.log(`| ${k + 1} | ${x.single.ms.toFixed(0)} | ${x.threaded.ms.toFixed(0)} | ${(x.threaded.ms / x.single.ms).toFixed(3)} |`));
  console.log(`median ratio ${median.toFixed(3)}; the same bytes in every run: ${same}`);
  if (!same) process.exitCode = 1;
} finally {
  await context.close();
  server.close();
  await rm(profile, { recursive: true, force: true });
}
