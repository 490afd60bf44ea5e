// The demo page's first and second visit (issue 21 item 6), for the bench's `page` section.
//
// The page (web/, built by Vite against this tree's dist/) is served with cacheable responses and
// opened in headless Chromium (playwright-core, /usr/bin/chromium) on one fresh browser profile:
// visit 1 starts with an empty cache; the browser is then closed and started again on the same
// profile for visit 2, which gets the page and its .wasm from the HTTP cache and V8's compiled
// code for the module from Chromium's code cache (the page compiles it with compileStreaming,
// whose code Chromium caches). Each visit: navigation until the worker's module answers (the
// version shown), load the model through the file input, set the edge length, remesh twice
// (the page's first call and a later call of the same worker).
//
// usage: node bench/tools/page_visits.mjs [MODEL] [EDGE_REL] [ROUNDS]
// Prints one JSON line per visit ({"round","visit",...}) and a last summary line
// ({"visits":[{visit, median of each field over the rounds}],"codeCacheBytes":...}).
import { mkdtemp, readFile, readdir, rm, stat } from 'node:fs/promises';
import { createServer } from 'node:http';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { build } from 'vite';

const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const [model = path.resolve(ROOT, '../shared/data/fandisk.off'), relArg = '0.004', roundsArg = '2'] = process.argv.slice(2);
const rounds = Math.max(1, Number(roundsArg));
const webDist = path.join(ROOT, 'web', 'dist');

const MIME = { '.html': 'text/html; charset=utf-8', '.js': 'text/javascript; charset=utf-8', '.css': 'text/css; charset=utf-8', '.wasm': 'application/wasm', '.png': 'image/png', '.obj': 'text/plain; charset=utf-8', '.off': 'text/plain; charset=utf-8' };

/** Static server for web/dist: Vite's hashed assets cacheable for a day, index.html revalidated. */
function serve(dir) {
  const server = createServer(async (req, res) => {
    try {
      const p = decodeURIComponent(new URL(req.url ?? '/', 'http://x').pathname);
      const file = path.normalize(path.join(dir, p.endsWith('/') ? `${p}index.html` : p));
      if (!file.startsWith(dir)) throw new Error('outside');
      const [body, st] = await Promise.all([readFile(file), stat(file)]);
      res.writeHead(200, {
        'content-type': MIME[path.extname(file)] ?? 'application/octet-stream',
        'cache-control': file.endsWith('.html') ? 'no-cache' : 'public, max-age=86400',
        'last-modified': st.mtime.toUTCString(),
      });
      res.end(body);
    } catch {
      res.writeHead(404).end('not found');
    }
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve({ server, url: `http://127.0.0.1:${server.address().port}/` })));
}

const launch = (profile) => chromium.launchPersistentContext(profile, {
  executablePath: '/usr/bin/chromium',
  headless: true,
  viewport: { width: 1500, height: 900 },
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
    '--disable-component-update', '--disable-sync', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});

const state = (page) => page.evaluate(() => document.body.dataset.state ?? '');
async function waitState(page, states, timeout) {
  await page.waitForFunction((s) => s.includes(document.body.dataset.state ?? ''), states, { timeout });
  return state(page);
}

/** Bytes under a directory (0 when it does not exist). */
async function duBytes(dir) {
  let n = 0;
  for (const e of await readdir(dir, { withFileTypes: true }).catch(() => [])) {
    const p = path.join(dir, e.name);
    n += e.isDirectory() ? await duBytes(p) : (await stat(p)).size;
  }
  return n;
}

/** One click of Remesh: page seconds (click to result in the page) and the library's own times. */
async function remeshOnce(page) {
  await page.click('[data-testid=remesh]');
  if ((await waitState(page, ['remeshed', 'error'], 300_000)) !== 'remeshed')
    throw new Error(`remesh failed in the page: ${await page.textContent('[data-testid=error]')}`);
  return page.evaluate(() => {
    const p = window.conformeshPage;
    const r = p.lastReport();
    return { pageSeconds: p.lastRemesh.seconds, librarySeconds: r.seconds.total, reportSeconds: r.seconds.report, triangles: r.triangles, hausdorffRel: r.hausdorffRel };
  });
}

async function visit(profile, url, round, n) {
  const context = await launch(profile);
  try {
    const page = context.pages()[0] ?? (await context.newPage());
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    await page.goto(url);
    // the module compiled and instantiated in the worker: its version is shown
    await page.waitForFunction(() => (document.querySelector('#version')?.textContent ?? '') !== '', undefined, { timeout: 120_000 });
    const moduleReadyMs = await page.evaluate(() => performance.now());
    await waitState(page, ['ready'], 60_000);
    await page.setInputFiles('#file-input', model);
    if ((await waitState(page, ['loaded', 'error'], 120_000)) !== 'loaded') throw new Error('the model did not load');
    const edge = page.locator('.lil-controller').filter({ hasText: 'edge length' }).locator('input').first();
    await edge.fill(relArg);
    await edge.press('Enter');
    const first = await remeshOnce(page);
    const second = await remeshOnce(page);
    if (errors.length) throw new Error(`page errors: ${errors.join(' | ')}`);
    return { round, visit: n, moduleReadyMs, first, second };
  } finally {
    await context.close();
  }
}

await build({ configFile: path.join(ROOT, 'web', 'vite.config.ts'), logLevel: 'error' });
const { server, url } = await serve(webDist);
const results = [];
let codeCacheBytes = [];
try {
  for (let round = 0; round < rounds; ++round) {
    const profile = await mkdtemp(path.join(tmpdir(), 'conformesh-visits-'));
    try {
      for (const n of [1, 2]) {
        const r = await visit(profile, url, round, n);
        if (n === 1) codeCacheBytes.push(await duBytes(path.join(profile, 'Default', 'Code Cache', 'wasm')));
        results.push(r);
        console.log(JSON.stringify(r));
      }
    } finally {
      await rm(profile, { recursive: true, force: true });
    }
  }
} finally {
  server.close();
}
const median = (xs) => {
  const v = xs.filter(Number.isFinite).sort((a, b) => a - b);
  return v.length ? (v.length % 2 ? v[(v.length - 1) / 2] : 0.5 * (v[v.length / 2 - 1] + v[v.length / 2])) : null;
};
const summary = [1, 2].map((n) => {
  const rs = results.filter((r) => r.visit === n);
  const m = (f) => median(rs.map(f));
  return {
    visit: n, moduleReadyMs: m((r) => r.moduleReadyMs),
    first: { pageSeconds: m((r) => r.first.pageSeconds), librarySeconds: m((r) => r.first.librarySeconds), reportSeconds: m((r) => r.first.reportSeconds) },
    second: { pageSeconds: m((r) => r.second.pageSeconds), librarySeconds: m((r) => r.second.librarySeconds), reportSeconds: m((r) => r.second.reportSeconds) },
    triangles: rs[0]?.first.triangles,
  };
});
console.log(JSON.stringify({ model: path.basename(model), edgeLengthRel: Number(relArg), rounds, visits: summary, codeCacheBytes: median(codeCacheBytes) }));
