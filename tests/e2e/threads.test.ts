// The threaded WebAssembly build (conformesh-mt) in headless Chromium. A cross-origin isolated
// page (COOP same-origin + COEP require-corp) runs one remesh on both cores; the same page
// without the headers runs the single-threaded build. Both give the native CLI's bytes, and the
// demo page works either way.
import { spawnSync } from 'node:child_process';
import { createHash } from 'node:crypto';
import { mkdtemp, readFile, rm } from 'node:fs/promises';
import { createServer, type Server } from 'node:http';
import { tmpdir } from 'node:os';
import { extname, join, normalize } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium, type BrowserContext, type Page } from 'playwright-core';
import { build } from 'vite';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { cancelLongRemesh } from './cancel.ts';
import { listenLocal } from './listen.ts';

const root = fileURLToPath(new URL('../../', import.meta.url));
const data = join(root, '..', 'shared', 'data');
const native = join(root, 'build', 'native', 'conformesh');

const MIME: Record<string, string> = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.wasm': 'application/wasm',
};

// The library's browser entry, the models in reach of fetch, and remesh() giving an output's
// SHA-256 (of its OFF bytes) and the call's time.
const testPage = `<!doctype html><html><head><meta charset="utf-8"></head><body><script type="module">
import { createRemesher, init } from '/dist/browser.js';
const hex = (b) => [...new Uint8Array(b)].map((x) => x.toString(16).padStart(2, '0')).join('');
window.threadsTest = {
  createRemesher,
  async remesh(r, name, options) {
    const bytes = new Uint8Array(await (await fetch('/data/' + name)).arrayBuffer());
    const mesh = await r.readMesh(bytes, { fileName: name });
    const t0 = performance.now();
    const res = await r.remesh(mesh, options);
    const ms = performance.now() - t0;
    const off = await r.writeMesh(res.mesh, 'off');
    return { ms, sha: hex(await crypto.subtle.digest('SHA-256', off)), triangles: res.report.triangles };
  },
  // the same on the page's own thread (init(): the synchronous API)
  async remeshHere(name, options) {
    const cm = await init();
    const bytes = new Uint8Array(await (await fetch('/data/' + name)).arrayBuffer());
    const res = cm.remesh(cm.readMesh(bytes, { fileName: name }), options);
    const off = cm.writeMesh(res.mesh, 'off');
    return { threads: cm.threads, sha: hex(await crypto.subtle.digest('SHA-256', off)) };
  },
};
</script></body></html>`;

/** Serve the repository (and /data/ from shared/data, /page/ from `pageDir`), isolated or not. */
function serve(isolated: boolean, pageDir?: string): Promise<{ server: Server; url: string }> {
  const server = createServer(async (req, res) => {
    const headers: Record<string, string> = isolated
      ? { 'cross-origin-opener-policy': 'same-origin', 'cross-origin-embedder-policy': 'require-corp' }
      : {};
    try {
      const path = decodeURIComponent(new URL(req.url ?? '/', 'http://x').pathname);
      if (path === '/threads.html') {
        res.writeHead(200, { ...headers, 'content-type': MIME['.html']! }).end(testPage);
        return;
      }
      const [base, rest] = path.startsWith('/data/') ? [data, path.slice(6)]
        : path.startsWith('/page/') && pageDir ? [pageDir, path.slice(6) || 'index.html'] : [root, path];
      const file = normalize(join(base, rest));
      if (!file.startsWith(base)) throw new Error('outside');
      const body = await readFile(file);
      res.writeHead(200, { ...headers, 'content-type': MIME[extname(file)] ?? 'application/octet-stream' }).end(body);
    } catch {
      res.writeHead(404).end('not found');
    }
  });
  return listenLocal(server);
}

/** The native CLI's output for the same call: SHA-256 of its OFF file. */
function nativeSha(name: string, rel: number, dir: string): string {
  const out = join(dir, `${name}.${rel}.off`);
  const r = spawnSync(native, ['remesh', join(data, name), '-o', out, '--no-hausdorff', '--edge-length-rel', String(rel)], { encoding: 'utf8' });
  expect(r.status, r.stderr).toBe(0);
  return createHash('sha256').update(spawnSync('cat', [out]).stdout).digest('hex');
}

interface Run { ms: number; sha: string; triangles: number }
type Win = {
  threadsTest: {
    createRemesher: (o: object) => unknown;
    remesh: (r: unknown, name: string, o: object) => Promise<Run>;
    remeshHere: (name: string, o: object) => Promise<{ threads: number; sha: string }>;
  };
};

const small: [string, number][] = [['fandisk.off', 0.02], ['mech-holes-shark.off', 0.03]];

describe('threaded WebAssembly build in headless Chromium', () => {
  let context: BrowserContext;
  let profile = '';
  let tmp = '';
  const servers: Server[] = [];
  const errors: string[] = [];

  const open = async (url: string): Promise<Page> => {
    const page = await context.newPage();
    page.on('pageerror', (e) => errors.push(`pageerror: ${e.message}`));
    await page.goto(url);
    return page;
  };
  /** The test page, served cross-origin isolated or not, with the library loaded. */
  const openTestPage = async (isolated: boolean): Promise<Page> => {
    const { server, url } = await serve(isolated);
    servers.push(server);
    const page = await open(`${url}threads.html`);
    await page.waitForFunction(() => 'threadsTest' in window);
    expect(await page.evaluate(() => crossOriginIsolated)).toBe(isolated);
    return page;
  };

  beforeAll(async () => {
    profile = await mkdtemp(join(tmpdir(), 'conformesh-chromium-'));
    tmp = await mkdtemp(join(tmpdir(), 'conformesh-threads-'));
    context = await chromium.launchPersistentContext(profile, {
      executablePath: '/usr/bin/chromium',
      headless: true,
      args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
        '--disable-background-networking', '--disable-component-update', '--disable-sync',
        '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
    });
  });

  afterAll(async () => {
    await context?.close();
    for (const s of servers) s.close();
    if (profile) await rm(profile, { recursive: true, force: true });
    if (tmp) await rm(tmp, { recursive: true, force: true });
  });

  it('isolated: the threaded build gives the single-threaded build\'s and the native CLI\'s bytes, (fandisk at 0.004 timed on 1 and 2 threads)', async () => {
    const page = await openTestPage(true);
    const r = await page.evaluate(async (models) => {
      const t = (window as unknown as Win).threadsTest;
      type R = { threads(): Promise<number>; terminate(): void };
      const one = t.createRemesher({ workers: 1, init: { threads: 1 } }) as R;
      const mt = t.createRemesher({ workers: 1 }) as R;
      const here = await t.remeshHere(models[0]![0], { targetEdgeLengthRel: models[0]![1], computeHausdorff: false });
      const out = { here, threads: [await one.threads(), await mt.threads()], small: [] as [Run, Run, Run][], single: [] as number[], two: [] as number[], mtOne: [] as number[] };
      for (const [name, rel] of models) {
        const o = { targetEdgeLengthRel: rel, computeHausdorff: false };
        out.small.push([await t.remesh(one, name, o), await t.remesh(mt, name, o), await t.remesh(mt, name, { ...o, threads: 1 })]);
      }
      // pairs in turn, the page's defaults otherwise (the report's distance included)
      for (let k = 0; k < 2; ++k) {
        out.single.push((await t.remesh(one, 'fandisk.off', { targetEdgeLengthRel: 0.004 })).ms);
        out.two.push((await t.remesh(mt, 'fandisk.off', { targetEdgeLengthRel: 0.004 })).ms);
      }
      out.mtOne.push((await t.remesh(mt, 'fandisk.off', { targetEdgeLengthRel: 0.004, threads: 1 })).ms);
      one.terminate();
      mt.terminate();
      return out;
    }, small);
    expect(r.threads[0]).toBe(1);
    expect(r.threads[1]).toBeGreaterThan(1);
    // the page's own thread: the threaded build too, the same bytes
    expect(r.here.threads).toBeGreaterThan(1);
    expect(r.here.sha).toBe(nativeSha(small[0]![0], small[0]![1], tmp));
    small.forEach(([name, rel], i) => {
      const [single, threaded, threadedOne] = r.small[i]!;
      const expected = nativeSha(name, rel, tmp);
      expect(single.sha, `${name} single-threaded build vs native`).toBe(expected);
      expect(threaded.sha, `${name} threaded build vs native`).toBe(expected);
      expect(threadedOne.sha, `${name} threaded build on one thread vs native`).toBe(expected);
    });
    const ratios = r.single.map((s, k) => r.two[k]! / s).sort((a, b) => a - b);
    const median = (ratios[0]! + ratios[ratios.length - 1]!) / 2;
    console.log(`fandisk 0.004 in Chromium: single-threaded build ${r.single.map(Math.round).join(', ')} ms; threaded build, ${r.threads[1]} threads ${r.two.map(Math.round).join(', ')} ms, 1 thread ${r.mtOne.map(Math.round).join(', ')} ms; ratio ${median.toFixed(2)}`);
    expect(errors).toEqual([]);
  });

  it('not isolated: the single-threaded build, the same bytes', async () => {
    const page = await openTestPage(false);
    const r = await page.evaluate(async ([name, rel]) => {
      const t = (window as unknown as Win).threadsTest;
      const rm = t.createRemesher({ workers: 1 }) as { threads(): Promise<number>; terminate(): void };
      const out = { threads: await rm.threads(), run: await t.remesh(rm, name, { targetEdgeLengthRel: rel, computeHausdorff: false, threads: 2 }) };
      rm.terminate();
      return out;
    }, small[0]!);
    expect(r.threads).toBe(1);
    expect(r.run.sha).toBe(nativeSha(small[0]![0], small[0]![1], tmp));
    expect(errors).toEqual([]);
  });

  for (const isolated of [true, false]) {
    it(`the demo page remeshes fandisk ${isolated ? 'cross-origin isolated, on every core' : 'without isolation, on one thread'}`, async () => {
      const out = join(tmp, 'page');
      // built once, by the first of the two
      if (isolated) await build({ configFile: join(root, 'web', 'vite.config.ts'), logLevel: 'error', build: { outDir: out, emptyOutDir: true } });
      const { server, url } = await serve(isolated, out);
      servers.push(server);
      const page = await open(`${url}page/`);
      await page.waitForFunction(() => document.body.dataset.state === 'ready', undefined, { timeout: 60_000 });
      expect(await page.evaluate(() => crossOriginIsolated)).toBe(isolated);
      await page.setInputFiles('#file-input', join(data, 'fandisk.off'));
      await page.waitForFunction(() => ['loaded', 'error'].includes(document.body.dataset.state ?? ''), undefined, { timeout: 60_000 });
      await page.click('[data-testid=remesh]');
      await page.waitForFunction(() => ['remeshed', 'error'].includes(document.body.dataset.state ?? ''), undefined, { timeout: 100_000 });
      expect(await page.evaluate(() => document.body.dataset.state)).toBe('remeshed');
      const remeshThreads = () => page.evaluate(() => (window as unknown as { conformeshPage: { remeshThreads(): Promise<number> } }).conformeshPage.remeshThreads());
      const threads = await remeshThreads();
      if (isolated) expect(threads).toBeGreaterThan(1);
      else expect(threads).toBe(1);
      // a cancel stops the call's worker (and a threaded build's own workers); the page's next
      // remesh runs on a fresh worker with as many threads
      await cancelLongRemesh(page);
      await page.click('[data-testid=remesh]');
      await page.waitForFunction(() => ['remeshed', 'error'].includes(document.body.dataset.state ?? ''), undefined, { timeout: 100_000 });
      expect(await page.evaluate(() => document.body.dataset.state)).toBe('remeshed');
      expect(await remeshThreads()).toBe(threads);
      expect(errors).toEqual([]);
      await page.close();
    });
  }
});
