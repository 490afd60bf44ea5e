// The demo page end to end, in headless Chromium (playwright-core + Debian chromium, SwiftShader
// WebGL): build the page with Vite, serve it, upload ../shared/data/fandisk.off, remesh it, check
// the quality table, that the three views are drawn, that the main thread stays responsive, and
// that a corrupt file gives a readable error. Screenshots go to test-results/.
import { mkdir, mkdtemp, readFile, rm, writeFile } from 'node:fs/promises';
import { createServer, type Server } from 'node:http';
import { tmpdir } from 'node:os';
import { extname, join, normalize } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium, type BrowserContext, type Page } from 'playwright-core';
import { build } from 'vite';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { createRemesher, readMesh } from '../../dist/index.js';
import { decodePng, pixelStats } from './png.ts';

const root = fileURLToPath(new URL('../../', import.meta.url));
const webDist = join(root, 'web', 'dist');
const results = join(root, 'test-results');
const fandisk = join(root, '..', 'shared', 'data', 'fandisk.off');

// Whether this build of the package has the remesh binding (decides remesh test vs visible todo).
const probeRemesher = createRemesher();
const HAS_REMESH = typeof (probeRemesher as unknown as { remesh?: unknown }).remesh === 'function';
probeRemesher.terminate();

const MIME: Record<string, string> = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.wasm': 'application/wasm',
  '.obj': 'text/plain; charset=utf-8',
  '.png': 'image/png',
};

function serve(dir: string): Promise<{ server: Server; url: string }> {
  const server = createServer(async (req, res) => {
    try {
      const path = decodeURIComponent(new URL(req.url ?? '/', 'http://x').pathname);
      const file = normalize(join(dir, path.endsWith('/') ? `${path}index.html` : path));
      if (!file.startsWith(dir)) throw new Error('outside');
      const body = await readFile(file);
      res.writeHead(200, { 'content-type': MIME[extname(file)] ?? 'application/octet-stream' });
      res.end(body);
    } catch {
      res.writeHead(404).end('not found');
    }
  });
  return new Promise((resolve) => {
    server.listen(0, '127.0.0.1', () => {
      const addr = server.address();
      resolve({ server, url: `http://127.0.0.1:${typeof addr === 'object' && addr ? addr.port : 0}/` });
    });
  });
}

let server: Server | undefined;
let context: BrowserContext | undefined;
let profile: string | undefined;
let page: Page;
const pageErrors: string[] = [];

async function shot(name: string): Promise<void> {
  await page.screenshot({ path: join(results, `page-${name}.png`) });
}

/** Luminance variance and non-background share of a view's canvas, from a screenshot of it. */
async function canvasStats(testid: string, name: string) {
  await page.evaluate(() => (window as unknown as { conformeshPage: { renderAll(): void } }).conformeshPage.renderAll());
  const png = await page.locator(`[data-testid=${testid}] canvas`).screenshot();
  await writeFile(join(results, `page-${name}.png`), png);
  return pixelStats(decodePng(png));
}

async function waitState(states: string[], timeout: number): Promise<string> {
  await page.waitForFunction((s) => s.includes(document.body.dataset.state ?? ''), states, { timeout });
  return page.evaluate(() => document.body.dataset.state ?? '');
}

describe('demo page in headless Chromium', () => {
  beforeAll(async () => {
    await mkdir(results, { recursive: true });
    await build({ configFile: join(root, 'web', 'vite.config.ts'), logLevel: 'error' });
    ({ server, url: pageUrl } = await serve(webDist));
    profile = await mkdtemp(join(tmpdir(), 'conformesh-chromium-'));
    context = await chromium.launchPersistentContext(profile, {
      executablePath: '/usr/bin/chromium',
      headless: true,
      viewport: { width: 1500, height: 900 },
      args: [
        '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
        '--disable-background-networking', '--disable-component-update', '--disable-sync',
        '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
      ],
    });
    page = context.pages()[0] ?? (await context.newPage());
    page.on('pageerror', (e) => pageErrors.push(`pageerror: ${e.message}`));
    page.on('console', (m) => {
      if (m.type() === 'error') pageErrors.push(`console.error: ${m.text()}`);
    });
    await page.goto(pageUrl);
    await waitState(['ready'], 30_000);
  });

  afterAll(async () => {
    await context?.close();
    server?.close();
    if (profile) await rm(profile, { recursive: true, force: true });
  });

  let pageUrl = '';

  it('loads fandisk.off through the file input and draws the input view', async () => {
    await page.setInputFiles('#file-input', fandisk);
    expect(await waitState(['loaded', 'error'], 30_000)).toBe('loaded');
    const expected = await readMesh(await readFile(fandisk), 'off');
    expect(await page.textContent('[data-testid=q-in-triangles]')).toBe(String(expected.triangles.length / 3));
    expect(await page.textContent('[data-testid=q-in-vertices]')).toBe(String(expected.positions.length / 3));
    const minIn = parseFloat((await page.textContent('[data-testid=q-in-minAngle]')) ?? '');
    expect(minIn).toBeGreaterThan(0);
    expect(minIn).toBeLessThan(60);
    const s = await canvasStats('canvas-input', 'input-view');
    expect(s.variance).toBeGreaterThan(20);
    expect(s.nonBackground).toBeGreaterThan(0.05);
    await shot('loaded');
    if (!HAS_REMESH) {
      // the page must say so, not show an empty or fake result
      expect(await page.isDisabled('[data-testid=remesh]')).toBe(true);
      expect(await page.textContent('#remesh-unavailable')).toMatch(/not available in this build/);
    }
  });

  if (HAS_REMESH) {
    it('cancels a running remesh from the Cancel button', async () => {
      await page.click('[data-testid=remesh]');
      await page.waitForFunction(() => document.body.dataset.state === 'remeshing', undefined, { timeout: 10_000 });
      await page.click('[data-testid=cancel]');
      expect(await waitState(['loaded', 'error', 'remeshed'], 10_000)).toBe('loaded');
      expect(await page.textContent('[data-testid=notice]')).toMatch(/cancelled/i);
    });

    it('remeshes fandisk in the worker: the table reports the exported mesh, input and remesh views drawn', async () => {
      await page.click('[data-testid=remesh]');
      const state = await waitState(['remeshed', 'error'], 100_000);
      if (state === 'error') throw new Error(`remesh failed in the page: ${await page.textContent('[data-testid=error]')}`);
      const minOut = parseFloat((await page.textContent('[data-testid=q-out-minAngle]')) ?? '');
      expect(Number.isFinite(minOut)).toBe(true);
      const triangles = Number(await page.textContent('[data-testid=q-out-triangles]'));
      expect(Number.isInteger(triangles) && triangles > 0).toBe(true);
      const timing = await page.evaluate(() => (window as unknown as { conformeshPage: { lastRemesh: Record<string, number> } }).conformeshPage.lastRemesh);
      console.log(`remesh in page: ${JSON.stringify(timing)}`);
      expect(timing.frames).toBeGreaterThan(0);
      for (const [id, name] of [['canvas-input', 'input-view'], ['canvas-remesh', 'remesh-view']] as const) {
        const s = await canvasStats(id, `remeshed-${name}`);
        expect(s.variance, `${id} variance`).toBeGreaterThan(20);
        expect(s.nonBackground, `${id} drawn share`).toBeGreaterThan(0.05);
      }
      await shot('remeshed');
      // the exported OBJ is the remesh the table describes: same triangle count, same worst angle
      const [download] = await Promise.all([page.waitForEvent('download'), page.click('#export button[data-format=obj]')]);
      const exported = await readMesh(await readFile(await download.path()), 'obj');
      expect(exported.triangles.length / 3).toBe(triangles);
      expect(Math.abs(worstAngleDeg(exported) - minOut)).toBeLessThan(0.1);
    });

    it('the remesh of fandisk has min angle ≥ 30° away from the exempt input corners (fandisk has one of 19.4°)', async () => {
      const away = parseFloat((await page.textContent('[data-testid="q-out-report.minAngleOutsideExempt"]')) ?? '');
      expect(away).toBeGreaterThanOrEqual(30);
      expect(Number(await page.textContent('[data-testid="q-out-report.trianglesBelowBoundOutsideExempt"]'))).toBe(0);
      // the overall minimum is at an exempt corner: an input angle below 30°
      const minOut = parseFloat((await page.textContent('[data-testid=q-out-minAngle]')) ?? '');
      const minIn = parseFloat((await page.textContent('[data-testid=q-in-minAngle]')) ?? '');
      expect(minOut).toBeGreaterThan(0);
      if (minOut < 30) expect(Number(await page.textContent('[data-testid="q-out-report.exemptCorners.length"]'))).toBeGreaterThan(0);
      expect(minIn).toBeLessThan(30);
    });

    it('the main thread is never blocked > 100 ms during the remesh', async () => {
      // The rAF probe measures every gap between frames while the worker remeshes, three times:
      // the first remesh (right after the Cancel test, in a fresh worker) and two more. Every one
      // must stay under 100 ms. With the software GL here, anything that resizes or redraws a
      // WebGL view during the remesh stalls the main thread on the starved GPU process (the
      // first remesh's 130-415 ms gaps were the views resized by the cleared 'cancelled' notice).
      const lastRemesh = () => page.evaluate(() => (window as unknown as { conformeshPage: { lastRemesh: Record<string, number> } }).conformeshPage.lastRemesh);
      const runs = [await lastRemesh()];
      for (let i = 0; i < 2; ++i) {
        await page.click('[data-testid=remesh]');
        expect(await waitState(['remeshed', 'error'], 100_000)).toBe('remeshed');
        runs.push(await lastRemesh());
      }
      const gaps = runs.map((r) => r.maxFrameGapMs!);
      console.log(
        `max frame gap during the remesh, three runs: ${runs.map((r) => `${r.maxFrameGapMs!.toFixed(1)} ms (ending ${r.maxFrameGapEndMs!.toFixed(0)} ms into a ${(r.seconds! * 1000).toFixed(0)} ms remesh, ${r.frames} frames)`).join(', ')}`,
      );
      expect(Math.max(...gaps)).toBeLessThan(100);
    });

    it('the flattened-domain view draws every patch after a remesh', async () => {
      const flatMissing = await page.isVisible('#flat-unavailable');
      expect(flatMissing, `flattened-domain view not drawn: ${await page.textContent('#flat-unavailable')}`).toBe(false);
      const s = await canvasStats('canvas-flat', 'remeshed-flat-view');
      expect(s.variance).toBeGreaterThan(20);
    });
  } else {
    it.todo('remesh fandisk in the page (min angle ≥ 30°, 3 views drawn, frame gap < 100 ms): this build of the package has no remesh binding');
  }

  it('loads the bundled samples: spot.obj, the generated mounting plate, a binary STL', async () => {
    for (const [value, name] of [['plate', 'mounting-plate.off'], ['box-with-hole.stl', 'box-with-hole.stl'], ['spot', 'spot.obj']] as const) {
      await page.selectOption('#sample', value);
      await page.waitForFunction((n) => document.querySelector('[data-testid=mesh-name]')?.textContent?.startsWith(`${n}:`), name, { timeout: 30_000 });
      expect(await waitState(['loaded', 'error'], 30_000)).toBe('loaded');
      const s = await canvasStats('canvas-input', `sample-${value}`);
      expect(s.variance).toBeGreaterThan(20);
      expect(s.nonBackground).toBeGreaterThan(0.05);
      await shot(`sample-${value}`);
    }
    // a mesh with topology problems loads, and the page says what the library found
    await page.selectOption('#sample', 'needs-repair.obj');
    await page.waitForFunction(() => document.querySelector('[data-testid=mesh-name]')?.textContent?.startsWith('needs-repair.obj:'), undefined, { timeout: 30_000 });
    expect(await page.isVisible('[data-testid=notice]')).toBe(true);
    expect(await page.textContent('[data-testid=notice]')).toMatch(/Topology findings/);
  });

  it('shows a readable error, with its code and what to do, for a corrupt file', async () => {
    await page.setInputFiles('#file-input', {
      name: 'corrupt.off',
      mimeType: 'application/octet-stream',
      buffer: Buffer.from('OFF\n3 1 0\n0 0 0\n1 0 zebra\n0 1 0\n3 0 1 2\n'),
    });
    expect(await waitState(['error'], 30_000)).toBe('error');
    const box = page.locator('[data-testid=error]');
    expect(await box.isVisible()).toBe(true);
    expect(await page.textContent('[data-testid=error-code]')).toBe('ParseError');
    const text = (await box.textContent()) ?? '';
    expect(text).toMatch(/corrupt\.off/);
    expect(text).toMatch(/line 4/);
    expect(text).toMatch(/re-export/);
    await shot('corrupt-file');
    // the previous mesh is still shown, and nothing escaped as an uncaught exception
    const s = await canvasStats('canvas-input', 'input-after-error');
    expect(s.variance).toBeGreaterThan(20);
    expect(pageErrors).toEqual([]);
  });
});

/** Smallest corner angle (degrees) over all triangles of a mesh. */
function worstAngleDeg(mesh: { positions: Float64Array; triangles: Uint32Array }): number {
  const p = mesh.positions;
  const t = mesh.triangles;
  let worst = 180;
  for (let f = 0; f < t.length; f += 3) {
    for (let k = 0; k < 3; k++) {
      const a = t[f + k] * 3, b = t[f + ((k + 1) % 3)] * 3, c = t[f + ((k + 2) % 3)] * 3;
      const ux = p[b] - p[a], uy = p[b + 1] - p[a + 1], uz = p[b + 2] - p[a + 2];
      const vx = p[c] - p[a], vy = p[c + 1] - p[a + 1], vz = p[c + 2] - p[a + 2];
      const cx = uy * vz - uz * vy, cy = uz * vx - ux * vz, cz = ux * vy - uy * vx;
      const ang = Math.atan2(Math.hypot(cx, cy, cz), ux * vx + uy * vy + uz * vz) * 180 / Math.PI;
      if (ang < worst) worst = ang;
    }
  }
  return worst;
}
