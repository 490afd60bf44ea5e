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
import { cancelLongRemesh } from './cancel.ts';
import { listenLocal } from './listen.ts';
import { decodePng, pixelStats, type Image } from './png.ts';
import { stageFraction } from '../../web/src/stages.ts';
import { GROUPS, entryOf, reportValues, reportedStages, stageKey } from '../../web/src/quality.ts';
import type { RemeshReport } from '../../dist/index.js';
import { packBoxes, type Box2 } from '../../web/src/atlas.ts';
import { uniqueEdges } from '../../web/src/scenes.ts';

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
  return listenLocal(server);
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

/** Share of a view's surface pixels with a strong luminance step to their right neighbour (a checker texture has many). */
async function edgeDensity(testid: string, name: string): Promise<number> {
  await page.evaluate(() => (window as unknown as { conformeshPage: { renderAll(): void } }).conformeshPage.renderAll());
  const png = await page.locator(`[data-testid=${testid}] canvas`).screenshot();
  await writeFile(join(results, `page-${name}.png`), png);
  const img = decodePng(png);
  const bg = backgroundOf(img);
  const lum = (i: number) => 0.2126 * img.data[i]! + 0.7152 * img.data[i + 1]! + 0.0722 * img.data[i + 2]!;
  const isBg = (i: number) => Math.abs(img.data[i]! - bg[0]) + Math.abs(img.data[i + 1]! - bg[1]) + Math.abs(img.data[i + 2]! - bg[2]) <= 24;
  let surface = 0, steps = 0;
  for (let y = 0; y < img.height; ++y)
    for (let x = 0; x + 1 < img.width; ++x) {
      const i = 4 * (y * img.width + x);
      if (isBg(i) || isBg(i + 4)) continue;
      ++surface;
      if (Math.abs(lum(i) - lum(i + 4)) > 60) ++steps;
    }
  return steps / Math.max(surface, 1);
}

/** A CSS-pixel point of a view's canvas that shows a triangle: nearest the centre, its 5x5 neighbourhood all off the background. */
async function surfacePoint(testid: string): Promise<{ x: number; y: number }> {
  await page.evaluate(() => (window as unknown as { conformeshPage: { renderAll(): void } }).conformeshPage.renderAll());
  const canvas = page.locator(`[data-testid=${testid}] canvas`);
  const img = decodePng(await canvas.screenshot({ scale: 'css' }));
  const bg = backgroundOf(img);
  const off = (x: number, y: number) => {
    const i = 4 * (y * img.width + x);
    return Math.abs(img.data[i]! - bg[0]) + Math.abs(img.data[i + 1]! - bg[1]) + Math.abs(img.data[i + 2]! - bg[2]) > 24;
  };
  let best: { x: number; y: number; d: number } | undefined;
  for (let y = 3; y < img.height - 3; y += 2) {
    for (let x = 3; x < img.width - 3; x += 2) {
      const d = Math.hypot(x - img.width / 2, y - img.height / 2);
      if (best && d >= best.d) continue;
      let all = true;
      for (let dy = -2; dy <= 2 && all; ++dy) for (let dx = -2; dx <= 2 && all; ++dx) all = off(x + dx, y + dy);
      if (all) best = { x, y, d };
    }
  }
  if (!best) throw new Error(`${testid}: no pixel shows a triangle`);
  const box = (await canvas.boundingBox())!;
  return { x: box.x + best.x + 0.5, y: box.y + best.y + 0.5 };
}

/** The most common colour of an image (the view's clear colour). */
function backgroundOf(img: Image): [number, number, number] {
  const counts = new Map<number, number>();
  for (let i = 0; i < img.data.length; i += 4) {
    const key = (img.data[i]! << 16) | (img.data[i + 1]! << 8) | img.data[i + 2]!;
    counts.set(key, (counts.get(key) ?? 0) + 1);
  }
  const key = [...counts.entries()].reduce((a, b) => (b[1] > a[1] ? b : a))[0];
  return [(key >> 16) & 255, (key >> 8) & 255, key & 255];
}

interface SelectionState {
  selected: number | undefined;
  input: number[];
  flat: number[];
  remesh: number[];
  library: { inputFaces?: number[]; triangles?: number[] };
}
const selectionState = () =>
  page.evaluate(() => (window as unknown as { conformeshPage: { selectionState(): SelectionState } }).conformeshPage.selectionState());

/** Every time the page's error box was shown since the last call (its text), from a MutationObserver. */
async function errorsShown(): Promise<string[]> {
  return page.evaluate(() => {
    const w = window as unknown as { errorBoxLog: string[] };
    const seen = w.errorBoxLog.splice(0);
    const box = document.querySelector<HTMLElement>('[data-testid=error]')!;
    if (!box.hidden) seen.push(`still shown: ${box.textContent}`);
    return seen;
  });
}

interface RemeshTiming {
  /** Worst gap between frames from the click until the result arrived (the gap open then included). */
  remeshMaxGap: number;
  /** Longest main-thread task (Long Tasks API: 50 ms and over; 0 if none) that overlapped the remesh. */
  remeshMaxTask: number;
  /** Gaps from the result's arrival until the views were drawn, and the gap across the arrival. */
  applyGaps: number[];
  straddling: number;
  /** Main-thread ms of each step of the application, as the page measured them. */
  steps: Record<string, number>;
  remeshMs: number;
  applyMs: number;
  frames: number;
}

/**
 * Click Remesh with the test's own requestAnimationFrame probe running (injected, independent of
 * the page's), wait for the 'remeshed' state (the result applied and the three views drawn), and
 * return the frame gaps: over the remesh itself (click to the result's arrival in the page) and
 * over the result's application (arrival to the views drawn, plus the frame after).
 */
async function remeshWithProbe(): Promise<RemeshTiming> {
  await page.evaluate(() => {
    const rec = { frames: [] as number[], tasks: [] as { start: number; end: number }[], clickAt: NaN, stop: false, observer: undefined as PerformanceObserver | undefined };
    (window as unknown as { testProbe: typeof rec }).testProbe = rec;
    // every main-thread task of 50 ms or more: script, events, and the rendering steps (ResizeObserver, GL waits)
    rec.observer = new PerformanceObserver((list) => {
      for (const e of list.getEntries()) rec.tasks.push({ start: e.startTime, end: e.startTime + e.duration });
    });
    rec.observer.observe({ type: 'longtask' });
    document.querySelector('[data-testid=remesh]')!.addEventListener('click', () => { rec.clickAt = performance.now(); }, { once: true, capture: true });
    const tick = () => {
      if (rec.stop) return;
      rec.frames.push(performance.now());
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  });
  await page.click('[data-testid=remesh]');
  const state = await waitState(['remeshed', 'error'], 100_000);
  if (state === 'error') throw new Error(`remesh failed in the page: ${await page.textContent('[data-testid=error]')}`);
  type Win = { testProbe: { frames: number[]; tasks: { start: number; end: number }[]; clickAt: number; stop: boolean; observer: PerformanceObserver }; conformeshPage: { lastRemesh: Record<string, number> } };
  // one more frame after the application, so the last gap is closed
  await page.waitForFunction(() => {
    const w = window as unknown as Win;
    return w.testProbe.frames.some((t) => t > w.conformeshPage.lastRemesh.appliedAt!);
  }, undefined, { timeout: 10_000 });
  const r = await page.evaluate(() => {
    const w = window as unknown as Win;
    w.testProbe.stop = true;
    w.testProbe.tasks.push(...w.testProbe.observer.takeRecords().map((e) => ({ start: e.startTime, end: e.startTime + e.duration })));
    w.testProbe.observer.disconnect();
    const { resultAt, appliedAt, applySteps } = w.conformeshPage.lastRemesh as unknown as { resultAt: number; appliedAt: number; applySteps: Record<string, number> };
    return { frames: w.testProbe.frames, tasks: w.testProbe.tasks, clickAt: w.testProbe.clickAt, resultAt, appliedAt, applySteps };
  });
  expect(r.clickAt, 'click seen').toBeGreaterThan(0);
  expect(r.resultAt).toBeGreaterThan(r.clickAt);
  const gaps = (times: number[]) => times.slice(1).map((t, i) => t - times[i]!);
  const during = [r.clickAt, ...r.frames.filter((t) => t > r.clickAt && t < r.resultAt), r.resultAt];
  const firstAfter = r.frames.findIndex((t) => t >= r.resultAt);
  const endIdx = r.frames.findIndex((t) => t > r.appliedAt);
  const applying = [r.resultAt, ...r.frames.slice(firstAfter, endIdx + 1)];
  return {
    remeshMaxGap: Math.max(...gaps(during)),
    remeshMaxTask: Math.max(0, ...r.tasks.filter((k) => k.end > r.clickAt && k.start < r.resultAt).map((k) => k.end - k.start)),
    applyGaps: gaps(applying),
    straddling: firstAfter > 0 ? r.frames[firstAfter]! - r.frames[firstAfter - 1]! : NaN,
    steps: r.applySteps,
    remeshMs: r.resultAt - r.clickAt,
    applyMs: r.appliedAt - r.resultAt,
    frames: during.length - 2,
  };
}

const timings: RemeshTiming[] = [];
const describeTiming = (t: RemeshTiming) =>
  `remesh ${t.remeshMs.toFixed(0)} ms, ${t.frames} frames, max gap ${t.remeshMaxGap.toFixed(1)} ms, longest main-thread task ${t.remeshMaxTask.toFixed(0)} ms; ` +
  `application ${t.applyMs.toFixed(0)} ms, gaps [${t.applyGaps.map((g) => g.toFixed(0)).join(', ')}] ms, gap across the arrival ${t.straddling.toFixed(0)} ms; ` +
  `steps ${Object.entries(t.steps).map(([k, v]) => `${k} ${v.toFixed(0)}`).join(', ')} ms`;

/** The report of the page's last remesh, as the library returned it (typed arrays as arrays). */
const lastReport = () =>
  page.evaluate(() => (window as unknown as { conformeshPage: { lastReport(): unknown } }).conformeshPage.lastReport()) as Promise<RemeshReport>;

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
    // every time the error box is shown, with its text (the page turns uncaught errors into it)
    await page.evaluate(() => {
      const w = window as unknown as { errorBoxLog: string[] };
      w.errorBoxLog = [];
      const box = document.querySelector<HTMLElement>('[data-testid=error]')!;
      new MutationObserver(() => {
        if (!box.hidden) w.errorBoxLog.push(box.textContent ?? '');
      }).observe(box, { attributes: true, attributeFilter: ['hidden'], childList: true, subtree: true });
    });
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
    expect(await page.textContent('[data-testid="q-input.triangles"]')).toBe(String(expected.triangles.length / 3));
    expect(await page.textContent('[data-testid="q-input.vertices"]')).toBe(String(expected.positions.length / 3));
    const minIn = parseFloat((await page.textContent('[data-testid="q-input.minAngle"]')) ?? '');
    expect(minIn).toBeGreaterThan(0);
    expect(minIn).toBeLessThan(60);
    const s = await canvasStats('canvas-input', 'input-view');
    expect(s.variance).toBeGreaterThan(20);
    expect(s.nonBackground).toBeGreaterThan(0.05);
    await shot('loaded');
    // before a remesh the input shows the page's own patch preview, and says so
    expect(await page.textContent('#legend-input')).toMatch(/preview/);
    expect(await errorsShown()).toEqual([]);
    if (!HAS_REMESH) {
      // the page must say so, not show an empty or fake result
      expect(await page.isDisabled('[data-testid=remesh]')).toBe(true);
      expect(await page.textContent('#remesh-unavailable')).toMatch(/not available in this build/);
    }
  });

  if (HAS_REMESH) {
    it('cancels a running remesh from the Cancel button', async () => {
      await cancelLongRemesh(page);
      expect(await errorsShown()).toEqual([]);
    });

    it('remeshes fandisk in the worker: the table reports the exported mesh, all three views drawn, no error shown', async () => {
      const t = await remeshWithProbe();
      timings.push(t);
      console.log(`first remesh: ${describeTiming(t)}`);
      const minOut = parseFloat((await page.textContent('[data-testid=q-minAngle]')) ?? '');
      expect(Number.isFinite(minOut)).toBe(true);
      const triangles = Number(await page.textContent('[data-testid=q-triangles]'));
      expect(Number.isInteger(triangles) && triangles > 0).toBe(true);
      for (const [id, name] of [['canvas-input', 'input-view'], ['canvas-flat', 'flat-view'], ['canvas-remesh', 'remesh-view']] as const) {
        const s = await canvasStats(id, `remeshed-${name}`);
        expect(s.variance, `${id} variance`).toBeGreaterThan(20);
        expect(s.nonBackground, `${id} drawn share`).toBeGreaterThan(0.05);
      }
      await shot('remeshed');
      expect(await errorsShown(), 'error box shown during load or remesh').toEqual([]);
      // the exported OBJ is the remesh the table describes: same triangle count, same worst angle
      const [download] = await Promise.all([page.waitForEvent('download'), page.click('#export button[data-format=obj]')]);
      const exported = await readMesh(await readFile(await download.path()), 'obj');
      expect(exported.triangles.length / 3).toBe(triangles);
      expect(Math.abs(worstAngleDeg(exported) - minOut)).toBeLessThan(0.1);
    });

    it('every stage the library reported has its bar: each goes 0 -> 100 % within its own stage, in the library\u2019s order, and shows its time', async () => {
      type Log = { events: { stage: string; fraction: number }[]; bars: { stage: string; value: number }[] };
      const log = await page.evaluate(() => (window as unknown as { conformeshPage: { progressLog: Log } }).conformeshPage.progressLog);
      const report = await lastReport();
      const shown = await page.$$eval('#progress li', (lis) => lis.map((li) => ({
        stage: li.getAttribute('data-stage')!, className: li.className, name: li.firstElementChild!.textContent!, text: li.lastElementChild!.textContent!,
      })));
      const order = shown.map((b) => b.stage);
      // a bar for every stage the library named: in its progress events and in the report's times
      const reported = new Set([...log.events.map((e) => stageKey(e.stage)), ...reportedStages(report).map(stageKey)]);
      expect(reported.size).toBeGreaterThanOrEqual(reportedStages(report).length);
      for (const stage of reported) expect(order, `stage '${stage}' reported`).toContain(stage);
      expect(new Set(order).size, 'one bar per stage').toBe(order.length);
      // every bar is full, named in words, and shows its stage's time from the report
      for (const b of shown) {
        expect(b.className, `${b.stage} done`).toBe('done');
        expect(b.name, `${b.stage}: a name in words`).not.toMatch(/[a-z][A-Z]/);
      }
      for (const stage of reportedStages(report)) {
        const b = shown.find((x) => x.stage === stageKey(stage))!;
        expect(b.text, `${stage}'s time`).toBe(`${(report.seconds as unknown as Record<string, number>)[stage]!.toFixed(2)} s`);
      }
      // the library's overall fraction is monotone, and its stages come in the bars' order
      for (let i = 1; i < log.events.length; ++i) {
        expect(log.events[i]!.fraction).toBeGreaterThanOrEqual(log.events[i - 1]!.fraction);
        expect(order.indexOf(stageKey(log.events[i]!.stage))).toBeGreaterThanOrEqual(order.indexOf(stageKey(log.events[i - 1]!.stage)));
      }
      const completedAt: number[] = [];
      for (const stage of order) {
        const values = log.bars.map((u, i) => ({ ...u, i })).filter((u) => u.stage === stage);
        expect(values.length, `${stage} shown`).toBeGreaterThan(0);
        for (let k = 1; k < values.length; ++k) expect(values[k]!.value, `${stage} monotone`).toBeGreaterThanOrEqual(values[k - 1]!.value);
        expect(values.at(-1)!.value, `${stage} ends at 100 %`).toBe(1);
        completedAt.push(values.find((u) => u.value === 1)!.i);
        // a stage that reports along the way starts near 0 and reaches most of its bar by its own events
        const own = log.events.filter((e) => stageKey(e.stage) === stage);
        if (own.length >= 5) {
          expect(values[0]!.value, `${stage} starts near 0 %`).toBeLessThan(0.25);
          const ownMax = Math.max(...own.map((e) => stageFraction(e.stage, e.fraction) ?? 0));
          expect(ownMax, `${stage} reaches most of its bar itself`).toBeGreaterThan(0.75);
        }
      }
      for (let k = 1; k < completedAt.length; ++k) expect(completedAt[k], `${order[k]} completes after ${order[k - 1]}`).toBeGreaterThanOrEqual(completedAt[k - 1]!);
    });

    it('the quality table is in words, grouped Input / Output / Pipeline, with a known row for every key of the report', async () => {
      const report = await lastReport();
      const rows = await page.$$eval('#quality tbody', (bodies) => bodies.map((b) => ({
        group: b.getAttribute('data-group'),
        title: b.querySelector('tr.group th')?.textContent,
        rows: [...b.querySelectorAll('tr[data-key]')].map((tr) => ({
          key: tr.getAttribute('data-key')!, unknown: tr.getAttribute('data-unknown'), label: tr.children[0]!.textContent!, value: tr.children[1]!.textContent!,
        })),
      })));
      expect(rows.map((g) => [g.group, g.title])).toEqual(GROUPS.map((g) => [g.group, g.title]));
      for (const g of rows) expect(g.rows.length, `${g.title} has rows`).toBeGreaterThan(0);
      const all = rows.flatMap((g) => g.rows.map((r) => ({ ...r, group: g.group })));
      const keys = [...reportValues(report).keys()];
      for (const r of all) {
        // no raw key: no camelCase word, no dotted path
        expect(r.label, `label of ${r.key}`).not.toMatch(/[a-z][A-Z]|\w\.\w/);
        expect(r.value, `value of ${r.key}`).not.toMatch(/[a-z][A-Z]/);
      }
      // every value the library reported is in the table, under the table's own label and group
      for (const key of keys) {
        const row = all.find((r) => r.key === key);
        expect(row, `report key ${key} shown`).toBeDefined();
        expect(row!.unknown, `report key ${key} is in quality.ts`).toBeNull();
        expect([row!.group, row!.label]).toEqual([entryOf(key)!.group, entryOf(key)!.label]);
      }
      // the whole table as the user reads it (cells apart)
      const text = await page.innerText('#quality');
      for (const word of text.split(/[\s:()·,;]+/)) expect(word, 'a camelCase word in the table').not.toMatch(/[a-z][A-Z]/);
    });

    it('lists the exempt corners of report.exemptCorners, and dots them in the input and remesh views', async () => {
      const report = await lastReport();
      const listed = await page.$$eval('#exempt-corners li', (lis) => lis.map((li) => ({
        vertex: Number(li.getAttribute('data-vertex')), outputVertex: Number(li.getAttribute('data-output-vertex')), angle: Number(li.getAttribute('data-angle')), text: li.textContent!,
      })));
      expect(listed.map(({ vertex, outputVertex, angle }) => ({ vertex, outputVertex, angle })))
        .toEqual(report.exemptCorners.map(({ vertex, outputVertex, angle }) => ({ vertex, outputVertex, angle })));
      for (const [i, c] of report.exemptCorners.entries()) {
        expect(listed[i]!.text).toContain(`input vertex ${c.vertex}`);
        expect(listed[i]!.text).toContain(`${c.angle.toFixed(2)}°`);
      }
      expect(Number(await page.textContent('[data-testid=q-exemptCorners]'))).toBe(report.exemptCorners.length);
      // fandisk has a corner below 30° (the test above): the list is not empty
      expect(listed.length).toBeGreaterThan(0);
      // the dots sit on the corners: input vertices of the file, output vertices of the exported remesh
      const inputMesh = await readMesh(await readFile(fandisk), 'off');
      const [download] = await Promise.all([page.waitForEvent('download'), page.click('#export button[data-format=obj]')]);
      const outputMesh = await readMesh(await readFile(await download.path()), 'obj');
      const dots = await page.evaluate(() => (window as unknown as { conformeshPage: { cornerDots(): { input: number[]; remesh: number[]; inScene: { input: boolean; remesh: boolean } } } }).conformeshPage.cornerDots());
      expect(dots.inScene).toEqual({ input: true, remesh: true });
      const at = (m: { positions: Float64Array }, v: number) => Array.from(m.positions.subarray(3 * v, 3 * v + 3));
      const close = (a: number[], b: number[]) => a.every((x, k) => Math.abs(x - b[k]!) <= 1e-5 * (1 + Math.abs(b[k]!)));
      expect(dots.input.length).toBe(3 * report.exemptCorners.length);
      expect(dots.remesh.length).toBe(3 * report.exemptCorners.length);
      report.exemptCorners.forEach((c, i) => {
        expect(close(dots.input.slice(3 * i, 3 * i + 3), at(inputMesh, c.vertex)), `input dot ${i} on vertex ${c.vertex}`).toBe(true);
        expect(close(dots.remesh.slice(3 * i, 3 * i + 3), at(outputMesh, c.outputVertex)), `remesh dot ${i} on vertex ${c.outputVertex}`).toBe(true);
        // the corner is where the input vertex was
        expect(close(at(outputMesh, c.outputVertex), at(inputMesh, c.vertex)), `corner ${i} kept in place`).toBe(true);
      });
      // and they are the only triangles of the exported remesh below the bound
      const exempt = new Set(report.exemptCorners.flatMap((c) => Array.from(c.triangles)));
      const bound = 30;
      for (let t = 0; t < outputMesh.triangles.length / 3; ++t) {
        if (exempt.has(t)) continue;
        const one = { positions: outputMesh.positions, triangles: outputMesh.triangles.subarray(3 * t, 3 * t + 3) };
        expect(worstAngleDeg(one), `triangle ${t}, not exempt`).toBeGreaterThanOrEqual(bound - 1e-3);
      }
      await page.locator('#exempt-corners').screenshot({ path: join(results, 'page-exempt-corners.png') });
    });

    it('the report downloads as JSON: the library\u2019s report, as the table and the corner list show it', async () => {
      expect(await page.isDisabled('[data-testid=download-report]')).toBe(false);
      const [download] = await Promise.all([page.waitForEvent('download'), page.click('[data-testid=download-report]')]);
      expect(download.suggestedFilename()).toMatch(/^fandisk-remesh-report\.json$/);
      const json = JSON.parse(await readFile(await download.path(), 'utf8')) as RemeshReport;
      expect(json).toEqual(await lastReport());
      expect(json.triangles).toBe(Number(await page.textContent('[data-testid=q-triangles]')));
      expect(json.vertices).toBe(Number(await page.textContent('[data-testid=q-vertices]')));
      expect(`${json.minAngle.toFixed(2)}°`).toBe(await page.textContent('[data-testid=q-minAngle]'));
      expect(Object.keys(json.seconds)).toContain('total');
      const listed = await page.$$eval('#exempt-corners li', (lis) => lis.map((li) => Number(li.getAttribute('data-vertex'))));
      expect(json.exemptCorners.map((c) => c.vertex)).toEqual(listed);
      for (const c of json.exemptCorners) expect(Array.isArray(c.triangles) && c.triangles.every((t) => Number.isInteger(t))).toBe(true);
    });

    it('shows the stage, progress and elapsed time while a remesh runs, then the time it took', async () => {
      await page.evaluate(() => {
        const w = window as unknown as { statusLog: { text: string; state: string; at: number }[] };
        w.statusLog = [];
        const el = document.querySelector('[data-testid=run-status]')!;
        new MutationObserver(() => w.statusLog.push({ text: el.textContent ?? '', state: document.body.dataset.state ?? '', at: performance.now() }))
          .observe(el, { childList: true, characterData: true, subtree: true });
      });
      await page.click('[data-testid=remesh]');
      expect(await waitState(['remeshed', 'error'], 100_000)).toBe('remeshed');
      const log = await page.evaluate(() => (window as unknown as { statusLog: { text: string; state: string; at: number }[] }).statusLog);
      const during = log.filter((e) => e.state === 'remeshing' && !/^done/.test(e.text));
      // "refine · 63% · 1.2 s": a stage, a percentage and seconds, ticking while the worker runs
      const parsed = during.map((e) => /^(.+) · (\d+)% · (\d+\.\d) s$/.exec(e.text));
      for (const [i, m] of parsed.entries()) expect(m, `status while running: '${during[i]!.text}'`).not.toBeNull();
      const seconds = parsed.map((m) => Number(m![3]));
      const percents = parsed.map((m) => Number(m![2]));
      expect(seconds.length, 'status updates during the run').toBeGreaterThanOrEqual(3);
      for (let i = 1; i < seconds.length; ++i) {
        expect(seconds[i]).toBeGreaterThanOrEqual(seconds[i - 1]!);
        expect(percents[i]).toBeGreaterThanOrEqual(percents[i - 1]!);
      }
      expect(seconds.at(-1)!).toBeGreaterThan(0);
      expect(new Set(parsed.map((m) => m![1])).size, 'more than one stage named').toBeGreaterThan(1);
      const { seconds: took } = await page.evaluate(() => (window as unknown as { conformeshPage: { lastRemesh: { seconds: number } } }).conformeshPage.lastRemesh);
      const final = (await page.textContent('[data-testid=run-status]')) ?? '';
      expect(final).toBe(`done in ${took.toFixed(2)} s (library ${(await lastReport()).seconds.total.toFixed(2)} s)`);
      // the elapsed time shown last is at most what the whole call took
      expect(seconds.at(-1)!).toBeLessThanOrEqual(took + 0.05);
    });

    it('clicking a patch in any view highlights the same library patch in all three views', async () => {
      expect(await page.textContent('#legend-input')).toMatch(/library/);
      for (const view of ['canvas-input', 'canvas-remesh', 'canvas-flat']) {
        const at = await surfacePoint(view);
        await page.mouse.click(at.x, at.y);
        const s = await selectionState();
        expect(s.selected, `a patch selected by clicking ${view}`).toBeTypeOf('number');
        // the views highlight what the library's result says belongs to that patch
        expect(s.library.inputFaces!.length).toBeGreaterThan(0);
        expect(s.input, `${view}: input faces highlighted`).toEqual(s.library.inputFaces);
        expect(s.remesh, `${view}: remesh triangles highlighted`).toEqual(s.library.triangles);
        expect(s.flat, `${view}: flattened patch highlighted`).toEqual([s.selected]);
        for (const legend of ['#legend-input', '#legend-flat', '#legend-remesh']) {
          expect(await page.textContent(legend)).toContain(`selected patch ${s.selected}`);
        }
        await shot(`selected-from-${view}`);
      }
      // a click on the background clears the selection everywhere
      const box = (await page.locator('[data-testid=canvas-input] canvas').boundingBox())!;
      await page.mouse.click(box.x + 3, box.y + 3);
      const s = await selectionState();
      expect(s.selected).toBeUndefined();
      expect(s.flat.length).toBeGreaterThan(1);
      expect(await errorsShown()).toEqual([]);
    });

    it('exports an OBJ with conformal UVs: every corner has a vt in [0,1], patches do not overlap and are not flipped', async () => {
      expect(await page.isDisabled('#export button[data-format=obj-uv]')).toBe(false);
      const [uvDownload] = await Promise.all([page.waitForEvent('download'), page.click('#export button[data-format=obj-uv]')]);
      const [plainDownload] = await Promise.all([page.waitForEvent('download'), page.click('#export button[data-format=obj]')]);
      const text = await readFile(await uvDownload.path(), 'utf8');
      const plain = await readFile(await plainDownload.path(), 'utf8');
      const lines = text.split('\n');
      const vt = lines.filter((l) => l.startsWith('vt ')).map((l) => l.slice(3).trim().split(/\s+/).map(Number));
      const faces = lines.filter((l) => l.startsWith('f ')).map((l) => l.slice(2).trim().split(/\s+/).map((c) => c.split('/').map(Number)));
      expect(faces.length).toBe(Number(await page.textContent('[data-testid=q-triangles]')));
      for (const f of faces) {
        expect(f.length).toBe(3);
        for (const c of f) {
          expect(c.length, 'corner v/vt').toBe(2);
          expect(Number.isInteger(c[1]) && c[1]! >= 1 && c[1]! <= vt.length).toBe(true);
        }
      }
      for (const t of vt) {
        expect(t.length).toBe(2);
        for (const x of t) expect(x >= 0 && x <= 1, `vt ${t} in [0,1]`).toBe(true);
      }
      // the 3D part is the plain export: same lines without vt, same vertex indices per face
      const strip = (ls: string[]) => ls.filter((l) => !l.startsWith('vt ')).map((l) => (l.startsWith('f ') ? l.replace(/\/\d+/g, '') : l));
      expect(strip(lines)).toEqual(plain.split('\n'));
      // charts: faces joined by shared vt; one per patch
      const parent = vt.map((_, i) => i);
      const find = (x: number): number => (parent[x] === x ? x : (parent[x] = find(parent[x]!)));
      for (const f of faces) for (const c of f.slice(1)) parent[find(c[1]! - 1)] = find(f[0]![1]! - 1);
      const charts = new Map<number, { box: number[]; pos: number; neg: number }>();
      for (const f of faces) {
        const [a, b, c] = f.map((x) => vt[x[1]! - 1]!) as [number[], number[], number[]];
        const area = (b[0]! - a[0]!) * (c[1]! - a[1]!) - (c[0]! - a[0]!) * (b[1]! - a[1]!);
        const key = find(f[0]![1]! - 1);
        const ch = charts.get(key) ?? { box: [Infinity, Infinity, -Infinity, -Infinity], pos: 0, neg: 0 };
        for (const p of [a, b, c]) {
          ch.box = [Math.min(ch.box[0]!, p[0]!), Math.min(ch.box[1]!, p[1]!), Math.max(ch.box[2]!, p[0]!), Math.max(ch.box[3]!, p[1]!)];
        }
        if (area > 0) ch.pos++;
        else ch.neg++;
        charts.set(key, ch);
      }
      expect(charts.size).toBe(Number(await page.textContent('[data-testid=q-patches]')));
      const list = [...charts.values()];
      for (const ch of list) expect(ch.neg === 0 || ch.pos === 0, `chart orientation ${ch.pos} ccw / ${ch.neg} cw`).toBe(true);
      console.log(`UV atlas: ${vt.length} vt, ${list.length} charts, orientation ${list.filter((c) => c.neg === 0).length} ccw / ${list.filter((c) => c.pos === 0).length} cw`);
      for (let i = 0; i < list.length; ++i) {
        for (let j = i + 1; j < list.length; ++j) {
          const p = list[i]!.box, q = list[j]!.box;
          const overlap = p[0]! < q[2]! && q[0]! < p[2]! && p[1]! < q[3]! && q[1]! < p[3]!;
          expect(overlap, `charts ${i} and ${j} overlap: ${p} / ${q}`).toBe(false);
        }
      }
    });

    it('the remesh of fandisk has min angle ≥ 30° away from the exempt input corners (fandisk has one of 19.4°)', async () => {
      const away = parseFloat((await page.textContent('[data-testid=q-minAngleOutsideExempt]')) ?? '');
      expect(away).toBeGreaterThanOrEqual(30);
      expect(Number(await page.textContent('[data-testid=q-trianglesBelowBoundOutsideExempt]'))).toBe(0);
      // the overall minimum is at an exempt corner: an input angle below 30°
      const minOut = parseFloat((await page.textContent('[data-testid=q-minAngle]')) ?? '');
      const minIn = parseFloat((await page.textContent('[data-testid="q-input.minAngle"]')) ?? '');
      expect(minOut).toBeGreaterThan(0);
      if (minOut < 30) expect(Number(await page.textContent('[data-testid=q-exemptCorners]'))).toBeGreaterThan(0);
      expect(minIn).toBeLessThan(30);
    });

    it('the main thread is never blocked > 100 ms during the remesh', async () => {
      // Three remeshes: the first (right after the Cancel test, in a fresh worker) and two more.
      // In each, from the click on Remesh until the result arrives in the page, no main-thread task
      // may last 100 ms (Long Tasks API: script, events and the rendering steps alike). With the
      // software GL here, anything that resizes or redraws a WebGL view during the remesh stalls the
      // main thread on the starved GPU process (the first remesh's 130-415 ms were the views resized
      // by the cleared 'cancelled' notice): such a stall is one long task.
      // The test's rAF probe's frame gaps are reported, not bounded: on two cores they also open
      // while the main thread is idle, when V8's background optimizing compiles of the module hold
      // the renderer's thread pool that rasters the frames (a Chrome trace of a 110 ms gap: three
      // pool threads in wasm.TopTierCompilation for 158-504 ms, no main-thread task over 32 ms).
      // The gaps while the result is applied (views rebuilt and redrawn, one per frame) are only
      // reported: here each frame that shows a rebuilt view waits for SwiftShader to draw it
      // (GLES2::ReadPixels in the commit, 95-150 ms in a Chrome trace): the first remesh of a
      // page had 136-221 ms gaps there, runs 2-3 67-121 ms at most (3 runs of this file).
      for (let i = 0; i < 2; ++i) timings.push(await remeshWithProbe());
      timings.forEach((t, i) => console.log(`remesh run ${i + 1}: ${describeTiming(t)}`));
      // frames were drawn during every remesh (a page that drew none would not be responsive)
      for (const t of timings) expect(t.frames).toBeGreaterThan(0);
      expect(Math.max(...timings.map((t) => t.remeshMaxTask))).toBeLessThan(100);
    });

    it('the flattened-domain view draws every patch after a remesh', async () => {
      const flatMissing = await page.isVisible('#flat-unavailable');
      expect(flatMissing, `flattened-domain view not drawn: ${await page.textContent('#flat-unavailable')}`).toBe(false);
      const s = await canvasStats('canvas-flat', 'remeshed-flat-view');
      expect(s.variance).toBeGreaterThan(20);
    });

    // organic scans at the page's defaults, and spot with its uv seams carried (curves the output
    // keeps, which meet its creases at 21.7° and 30.8°); the seconds are printed, not asserted
    // (speed belongs to the benchmarks)
    it('armadillo, man, ChineseDragon-10kv and spot at the page defaults: no triangle below the bound outside exempt input corners', async () => {
      for (const name of ['armadillo.off', 'man.off', 'ChineseDragon-10kv.off', 'spot.obj']) {
        await page.setInputFiles('#file-input', join(root, '..', 'shared', 'data', name));
        expect(await waitState(['loaded', 'error'], 30_000), name).toBe('loaded');
        const t = await remeshWithProbe();
        const seconds = t.remeshMs / 1000;
        console.log(`${name} at the page defaults: ${seconds.toFixed(2)} s`);
        expect(Number(await page.textContent('[data-testid=q-trianglesBelowBoundOutsideExempt]')), name).toBe(0);
        expect(parseFloat((await page.textContent('[data-testid=q-minAngleOutsideExempt]')) ?? ''), name).toBeGreaterThanOrEqual(30);
        expect(await errorsShown(), name).toEqual([]);
      }
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

  it('spot: "checker uv" textures the input, and the remesh with the uvs carried over; off without uvs', async () => {
    await page.selectOption('#sample', 'plate');
    expect(await waitState(['loaded', 'error'], 30_000)).toBe('loaded');
    expect(await page.$eval('#show-input-texture', (e) => (e as HTMLInputElement).disabled)).toBe(true); // no uvs
    await page.selectOption('#sample', 'spot');
    await page.waitForFunction(() => document.querySelector('[data-testid=mesh-name]')?.textContent?.startsWith('spot.obj:'), undefined, { timeout: 30_000 });
    expect(await waitState(['loaded', 'error'], 30_000)).toBe('loaded');
    expect(await page.$eval('#show-input-texture', (e) => (e as HTMLInputElement).disabled)).toBe(false);
    const plain = await edgeDensity('canvas-input', 'spot-input');
    await page.click('#show-input-texture');
    const checker = await edgeDensity('canvas-input', 'spot-input-checker');
    expect(checker).toBeGreaterThan(2 * plain); // the checker's dark and light cells
    if (!HAS_REMESH) return;
    await page.click('[data-testid=remesh]');
    expect(await waitState(['remeshed', 'error'], 120_000)).toBe('remeshed');
    expect(await page.$eval('#show-remesh-texture', (e) => (e as HTMLInputElement).disabled)).toBe(false);
    const wire = await page.$eval('#show-remesh-wire', (e) => (e as HTMLInputElement).checked);
    if (wire) await page.click('#show-remesh-wire');
    const out = await edgeDensity('canvas-remesh', 'spot-remesh');
    await page.click('#show-remesh-texture');
    const outChecker = await edgeDensity('canvas-remesh', 'spot-remesh-checker');
    expect(outChecker).toBeGreaterThan(2 * out);
    await shot('spot-checker-uv');
    await page.click('#show-input-texture');
    await page.click('#show-remesh-texture');
    if (wire) await page.click('#show-remesh-wire');
  });

  it('a curved disk gets a flatten preview coloured by its conformal factor', async () => {
    // a paraboloid cap (one boundary loop, not developable: u varies), flattened on loading
    const n = 12;
    const lines: string[] = [];
    for (let j = 0; j <= n; ++j) {
      for (let i = 0; i <= n; ++i) {
        const x = -1 + (2 * i) / n, y = -1 + (2 * j) / n;
        lines.push(`v ${x} ${y} ${0.6 * (x * x + y * y)}`);
      }
    }
    const at = (i: number, j: number) => j * (n + 1) + i + 1;
    for (let j = 0; j < n; ++j) {
      for (let i = 0; i < n; ++i) lines.push(`f ${at(i, j)} ${at(i + 1, j)} ${at(i + 1, j + 1)}`, `f ${at(i, j)} ${at(i + 1, j + 1)} ${at(i, j + 1)}`);
    }
    await page.setInputFiles('#file-input', { name: 'cap.obj', mimeType: 'text/plain', buffer: Buffer.from(lines.join('\n')) });
    expect(await waitState(['loaded', 'error'], 30_000)).toBe('loaded');
    await page.waitForFunction(() => /conformal factor/.test(document.querySelector('#legend-flat')?.textContent ?? ''), undefined, { timeout: 30_000 });
    const legend = (await page.textContent('#legend-flat')) ?? '';
    const m = /u, (-?[0-9.]+) \(dark\) … (-?[0-9.]+) \(yellow\)/.exec(legend);
    expect(m, legend).not.toBeNull();
    expect(Number(m![2]) - Number(m![1]), 'range of u').toBeGreaterThan(0.05);
    const s = await canvasStats('canvas-flat', 'cap-flatten-preview');
    expect(s.variance).toBeGreaterThan(20);
    expect(s.nonBackground).toBeGreaterThan(0.05);
    expect(await errorsShown()).toEqual([]);
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

describe('page helpers', () => {
  it('uniqueEdges lists every edge of a triangle list once', () => {
    // two triangles sharing the edge 1-2, and a third on its own
    const e = uniqueEdges(Uint32Array.of(0, 1, 2, 2, 1, 3, 4, 5, 6), 7);
    const pairs = [...Array(e.length / 2).keys()].map((i) => [e[2 * i]!, e[2 * i + 1]!].sort().join('-')).sort();
    expect(pairs).toEqual(['0-1', '0-2', '1-2', '1-3', '2-3', '4-5', '4-6', '5-6']);
  });

  it('packBoxes never overlaps two boxes', () => {
    const boxes: Box2[] = [];
    for (let i = 0; i < 40; ++i) {
      const x = Math.sin(i) * 3, y = Math.cos(3 * i) * 2, w = 0.2 + (i % 7) * 0.3, h = 0.1 + (i % 5) * 0.45;
      boxes.push([x, y, x + w, y + h]);
    }
    const moved = packBoxes(boxes).map(({ dx, dy }, i) => [boxes[i]![0] + dx, boxes[i]![1] + dy, boxes[i]![2] + dx, boxes[i]![3] + dy]);
    for (let i = 0; i < moved.length; ++i) {
      for (let j = i + 1; j < moved.length; ++j) {
        const p = moved[i]!, q = moved[j]!;
        expect(p[0]! < q[2]! && q[0]! < p[2]! && p[1]! < q[3]! && q[1]! < p[3]!, `boxes ${i}, ${j}`).toBe(false);
      }
    }
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
