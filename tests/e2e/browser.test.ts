// The packed package in a browser: a tiny page importing 'conformesh' from the installed tarball,
// built with Vite, served over HTTP and opened in headless Chromium (playwright-core with the
// Debian chromium); the same page without a bundler, and under the Vite dev server. The page reads spot.obj on the main thread and in a module Web Worker
// (createRemesher), and reports the result on window.__result.
import { copyFileSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { readFile } from 'node:fs/promises';
import { createServer, type Server } from 'node:http';
import type { AddressInfo } from 'node:net';
import { tmpdir } from 'node:os';
import { extname, join, normalize } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { build, createServer as createViteServer, type ViteDevServer } from 'vite';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { packAndInstall } from '../js/pack.js';

const spot = fileURLToPath(new URL('../../../shared/data/spot.obj', import.meta.url));

const page = `<!doctype html>
<html><head><meta charset="utf-8"><title>conformesh e2e</title></head>
<body><script type="module" src="./main.js"></script></body></html>`;

const main = `
import { readMesh, writeMesh, createRemesher, ConformeshError } from 'conformesh';
async function run() {
  const bytes = new Uint8Array(await (await fetch('./spot.obj')).arrayBuffer());
  const m = await readMesh(bytes);
  const back = await readMesh(await writeMesh(m, 'stl'));
  const remesher = createRemesher({ workers: 1 });
  const w = await remesher.readMesh(bytes);
  remesher.terminate();
  let code = '';
  try { await readMesh('not a mesh'); } catch (e) { code = e instanceof ConformeshError ? e.code : String(e); }
  return { nV: m.positions.length / 3, nF: m.triangles.length / 3, stlF: back.triangles.length / 3,
           workerF: w.triangles.length / 3, workerSame: w.positions.every((x, i) => x === m.positions[i]), code };
}
run().then((r) => { window.__result = r; }, (e) => { window.__result = { error: String(e && e.stack || e) }; });
`;

const types: Record<string, string> = {
  '.html': 'text/html',
  '.js': 'text/javascript',
  '.mjs': 'text/javascript',
  '.wasm': 'application/wasm',
  '.obj': 'text/plain',
};

describe('browser: Vite-built page using the installed package, in headless Chromium', () => {
  let dir = '';
  let profile = '';
  let server: Server;
  let url = '';

  beforeAll(async () => {
    dir = packAndInstall('browser');
    writeFileSync(join(dir, 'index.html'), page);
    writeFileSync(join(dir, 'main.js'), main);
    await build({
      root: dir,
      logLevel: 'warn',
      configFile: false,
      base: './',
      build: { outDir: join(dir, 'out'), target: 'es2022' },
    });
    copyFileSync(spot, join(dir, 'out', 'spot.obj'));
    copyFileSync(spot, join(dir, 'spot.obj'));
    // The same page without a bundler: a plain <script type=module> importing the installed files
    // (the browser entry, what package.json "exports" gives a browser; dist/index.js is Node's).
    writeFileSync(join(dir, 'plain.html'), page.replace('./main.js', './plain.js'));
    writeFileSync(join(dir, 'plain.js'), main.replace("from 'conformesh'", "from './node_modules/conformesh/dist/browser.js'"));
    const out = dir;
    server = createServer((req, res) => {
      const path = normalize(join(out, decodeURIComponent(new URL(req.url ?? '/', 'http://x').pathname)));
      const file = path.endsWith('/') || path === out ? join(path, 'index.html') : path;
      if (!file.startsWith(out)) {
        res.writeHead(403).end();
        return;
      }
      readFile(file).then(
        (body) => res.writeHead(200, { 'content-type': types[extname(file)] ?? 'application/octet-stream' }).end(body),
        () => res.writeHead(404).end(),
      );
    });
    await new Promise<void>((resolve) => server.listen(0, '127.0.0.1', resolve));
    url = `http://127.0.0.1:${(server.address() as AddressInfo).port}/`;
    profile = mkdtempSync(join(tmpdir(), 'conformesh-chromium-'));
  });

  afterAll(async () => {
    await new Promise((resolve) => server?.close(resolve));
    rmSync(dir, { recursive: true, force: true });
    rmSync(profile, { recursive: true, force: true });
  });

  async function resultOf(pageUrl: string): Promise<unknown> {
    const context = await chromium.launchPersistentContext(profile, {
      executablePath: '/usr/bin/chromium',
      headless: true,
      args: [
        '--headless',
        '--no-sandbox',
        '--disable-gpu',
        '--disable-quic',
        '--no-first-run',
        '--disable-background-networking',
        '--disable-component-update',
        '--disable-sync',
        '--use-angle=swiftshader',
        '--enable-unsafe-swiftshader',
      ],
    });
    try {
      const p = await context.newPage();
      const errors: string[] = [];
      p.on('pageerror', (e) => errors.push(String(e)));
      await p.goto(pageUrl);
      await p.waitForFunction(() => (window as unknown as { __result?: unknown }).__result !== undefined, null, {
        timeout: 60_000,
      });
      const result = await p.evaluate(() => (window as unknown as { __result: unknown }).__result);
      expect(errors).toEqual([]);
      return result;
    } finally {
      await context.close();
    }
  }

  const expected = { nV: 2930, nF: 5856, stlF: 5856, workerF: 5856, workerSame: true, code: 'ParseError' };

  it.each(['out/index.html', 'plain.html'])('%s loads the module, reads spot.obj on the main thread and in a module worker', async (pagePath) => {
    expect(await resultOf(url + pagePath)).toEqual(expected);
  });

  it('the same page under the Vite dev server (default config, dependency pre-bundling on)', async () => {
    let vite: ViteDevServer | undefined;
    try {
      vite = await createViteServer({ root: dir, configFile: false, logLevel: 'warn', server: { port: 0, host: '127.0.0.1' } });
      await vite.listen();
      expect(await resultOf(`${vite.resolvedUrls!.local[0]}index.html`)).toEqual(expected);
    } finally {
      await vite?.close();
    }
  });
});
