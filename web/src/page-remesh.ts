// A remesh run (progress, cancel, applying the result one view per frame) and the exports.
import type { RemeshReport } from 'conformesh';
import { objWithUvs, uvAtlas, type UvAtlas } from './atlas.ts';
import { clearError, showError } from './errors.ts';
import { minAnglePerTriangle } from './geometry.ts';
import type { Viewport } from './viewport.ts';
import { $, analyzer, engine, errorBox, lastRemesh, notice, page, params, probe, progress, setState, toggles, updateButtons } from './page.ts';
import {
  buildFlat, buildRemesh, ensureRemeshWire, exemptList, flatView, histogram, inputView, legend, qualityTable, refreshInput, remeshView, views,
} from './page-views.ts';

const loadPanel = $('#load');

/**
 * While a remesh runs, the panel above the views keeps its height: the error or notice it clears
 * (e.g. "Remesh cancelled.") would otherwise let the views grow, and a resized WebGL canvas is
 * redrawn. With a software GL (SwiftShader, software compositing) the three redraws and their
 * synchronous read-backs waited on a GPU process starved by the worker: 180-360 ms frame gaps
 * at the start of the remesh after a cancel (Chrome trace: ResizeObserver -> Viewport.resize,
 * then Commit -> GLES2::ReadPixels). The hold is released when the result is applied (the views
 * are rebuilt then anyway) or the run ends.
 */
function holdLoadPanel(hold: boolean): void {
  loadPanel.style.minHeight = hold ? `${loadPanel.getBoundingClientRect().height}px` : '';
}

export async function remesh(): Promise<void> {
  if (!page.input || page.running || !engine.canRemesh) return;
  const seq = page.loadSeq;
  const ac = new AbortController();
  page.running = ac;
  updateButtons();
  holdLoadPanel(true);
  clearError(errorBox);
  notice(undefined);
  progress.reset();
  setState('remeshing');
  probe.reset();
  const t0 = performance.now();
  const bound = params.minAngle;
  progress.startRunStatus();
  try {
    const result = await engine.remesh(page.input.mesh, params, page.input.bounds.diagonal, (p) => progress.setProgress(p.stage, p.fraction), ac.signal);
    const resultAt = performance.now();
    const seconds = (resultAt - t0) / 1000;
    const gap = probe.read();
    if (seq !== page.loadSeq) return;
    progress.finish(result.report);
    progress.endRunStatus(`done in ${seconds.toFixed(2)} s (library ${result.report.seconds.total.toFixed(2)} s)`);
    const a = await analyzer.analyze(result.mesh, { angles: true });
    if (seq !== page.loadSeq) return;
    const t1 = performance.now();
    let atlas: UvAtlas | undefined;
    try {
      atlas = uvAtlas(result.mesh, result.patches, result.patchOfTriangle);
    } catch (e) {
      // the remesh stands; only the UV export is off (and the page says why)
      showError(errorBox, e, 'building the UV atlas of the remesh');
    }
    page.output = { result, atlas, angles: a.angles!, minAngles: minAnglePerTriangle(a.angles!), stats: a.stats!, seconds, bound };
    if (result.inputPatchOfFace) page.libraryPatchOfFace = result.inputPatchOfFace;
    page.selected = undefined;
    // Applying the result is split into tasks, one view per frame, so the page keeps drawing
    // frames in between (the main thread is never blocked for long, even with a software GL).
    const nextTask = () => new Promise<void>((resolve) => setTimeout(resolve, 0));
    const applySteps: Record<string, number> = {};
    const step = (name: string, f: () => void) => {
      const t = performance.now();
      f();
      applySteps[name] = performance.now() - t;
    };
    // one view per frame: build, let the frame with its render go out, then the next
    // (a hidden tab draws no frames: then the steps go on without waiting for one, at most a
    // second per view, so the result is in place and the Remesh button back when it is shown)
    const frameOrTimeout = (v: Viewport) =>
      document.hidden ? Promise.resolve() : Promise.race([v.drawn(), new Promise<void>((resolve) => setTimeout(resolve, 1000))]);
    const drawn = async (v: Viewport) => {
      await frameOrTimeout(v);
      await nextTask();
    };
    holdLoadPanel(false);
    step('input', refreshInput);
    await drawn(inputView);
    if (seq !== page.loadSeq) return;
    step('flat', buildFlat);
    await drawn(flatView);
    if (seq !== page.loadSeq) return;
    step('remesh', buildRemesh);
    await drawn(remeshView);
    if (seq !== page.loadSeq) return;
    step('remeshWire', () => { if (toggles.remeshWire) ensureRemeshWire(); });
    await drawn(remeshView);
    if (seq !== page.loadSeq) return;
    step('panels', () => { qualityTable(); exemptList(); histogram(); legend(); });
    await Promise.all(views.map((v) => frameOrTimeout(v)));
    if (seq !== page.loadSeq) return;
    const appliedAt = performance.now();
    Object.assign(lastRemesh, {
      maxFrameGapMs: gap.maxGap, maxFrameGapEndMs: gap.maxGapAt - t0, frames: gap.frames, seconds,
      applyMs: appliedAt - t1, startAt: t0, resultAt, appliedAt, applySteps,
    });
    setState('remeshed');
  } catch (e) {
    if (seq !== page.loadSeq) return;
    const cancelled = (e as { code?: string }).code === 'Cancelled';
    progress.fail();
    const after = `after ${((performance.now() - t0) / 1000).toFixed(1)} s`;
    progress.endRunStatus(cancelled ? `cancelled ${after}` : `failed ${after}`);
    if (cancelled) {
      notice('Remesh cancelled.');
      setState('loaded');
    } else {
      showError(errorBox, e, 'remeshing');
      setState('error');
    }
  } finally {
    if (page.running === ac) page.running = undefined;
    holdLoadPanel(false);
    updateButtons();
  }
}

function download(bytes: Uint8Array, name: string): void {
  const url = URL.createObjectURL(new Blob([bytes as BlobPart], { type: 'application/octet-stream' }));
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

/** The report as JSON (typed arrays as arrays): what the library returned, nothing added. */
export function reportJson(report: RemeshReport): string {
  return JSON.stringify(report, (_k, v: unknown) => (ArrayBuffer.isView(v) ? Array.from(v as unknown as ArrayLike<number>) : v), 2);
}

export function downloadReport(): void {
  if (!page.output || !page.input) return;
  const base = page.input.name.replace(/\.[^.]*$/, '') + '-remesh';
  download(new TextEncoder().encode(reportJson(page.output.result.report) + '\n'), `${base}-report.json`);
}

export async function exportAs(format: string): Promise<void> {
  if (!page.output || !page.input) return;
  const base = page.input.name.replace(/\.[^.]*$/, '') + '-remesh';
  const m = page.output.result.mesh;
  try {
    if (format === 'obj-uv') {
      if (!page.output.atlas) return;
      const plain = new TextDecoder().decode(await engine.write({ positions: m.positions, triangles: m.triangles }, 'obj'));
      download(new TextEncoder().encode(objWithUvs(plain, m, page.output.atlas)), `${base}-uv.obj`);
    } else {
      const f = format as 'obj' | 'stl' | 'ply';
      download(await engine.write({ positions: m.positions, triangles: m.triangles }, f), `${base}.${f}`);
    }
  } catch (e) {
    showError(errorBox, e, `writing ${format.toUpperCase()}`);
  }
}
