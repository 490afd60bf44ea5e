// The page's shared state and services: the loaded input and the last remesh, the parameters and
// toggles, the engine (the library in its worker), the analyzer, the progress panel and the buttons.
import type { MeshInfo } from 'conformesh';
import { Engine, NO_PATCH, type FlatPatch, type Mesh3, type Params, type RemeshOutput } from './engine.ts';
import type { UvAtlas } from './atlas.ts';
import { showError } from './errors.ts';
import { Analyzer } from './analysis.ts';
import type { AngleStats, Bounds, FeaturePreview } from './geometry.ts';
import { FrameProbe } from './probe.ts';
import { reportedStages } from './quality.ts';
import { ProgressPanel } from './progress-panel.ts';
import { exemptCornerPositions } from './report-panel.ts';

export const $ = <T extends HTMLElement = HTMLElement>(sel: string) => document.querySelector<T>(sel)!;
export const errorBox = $('#error');
const noticeBox = $('#notice');
export const probe = new FrameProbe();
export const analyzer = new Analyzer();

export interface Input {
  name: string;
  mesh: Mesh3;
  bounds: Bounds;
  angles: Float64Array;
  stats: AngleStats;
  info?: MeshInfo;
  preview: FeaturePreview;
}
export interface Output {
  result: RemeshOutput;
  /** The UV atlas of the OBJ export (undefined: the result has no refined patches). */
  atlas: UvAtlas | undefined;
  angles: Float64Array;
  minAngles: Float64Array;
  stats: AngleStats;
  seconds: number;
  /** The angle bound (°) the remesh was asked for. */
  bound: number;
}
/** What the page shows: the loaded input, the last remesh, the selection and the run in flight. */
export const page = {
  input: undefined as Input | undefined,
  output: undefined as Output | undefined,
  /** The patches flatten() gave a disk-like input before any remesh. */
  flatPatches: undefined as FlatPatch[] | undefined,
  /** Why flatten() could not map the input in one piece (shown in the flat view, not as an error). */
  flatPreviewFailure: undefined as string | undefined,
  libraryPatchOfFace: undefined as Uint32Array | undefined,
  selected: undefined as number | undefined,
  running: undefined as AbortController | undefined,
  /** Bumped by each load: an async step that sees another value belongs to an older mesh. */
  loadSeq: 0,
};
export const lastLoad = { analysisMs: NaN, buildMs: NaN, firstFrameMs: NaN };
/** The last remesh: the page probe's worst frame gap, and performance.now() at the click, the result's arrival and the end of its application. */
export const lastRemesh = {
  maxFrameGapMs: NaN, maxFrameGapEndMs: NaN, frames: 0, seconds: NaN, applyMs: NaN, startAt: NaN, resultAt: NaN, appliedAt: NaN,
  /** Main-thread time of each step of the result's application (ms). */
  applySteps: {} as Record<string, number>,
};

export const params: Params = { minAngle: 30, edgeLength: 0.02, featureAngle: 40, chordTolerance: 0.001, boundary: 'free' };
export const toggles = {
  features: true,
  patches: true,
  inputWire: false,
  inputTexture: false,
  layout: true,
  refined: true,
  remeshWire: true,
  remeshTexture: false,
};
/** The exempt corners' dots in views 1 and 3. */
export const CORNER_COLOR = 0xff3df0;

export function setState(s: string): void {
  document.body.dataset.state = s;
}

export const progress = new ProgressPanel($('#progress'), $('#run-status'), () => !!page.running);

export let engine: Engine;
try {
  engine = new Engine();
} catch (e) {
  showError(errorBox, e, 'starting the conformesh worker');
  throw e;
}
engine.version().then(
  (v) => {
    $('#version').textContent = `v${v}`;
    // the warm-up's report names the stages the library reports: one bar each, before any run
    void engine.warmUp().then((r) => { if (r) progress.addBars(reportedStages(r)); });
  },
  (e) => showError(errorBox, e, 'loading the conformesh module'),
);

/** Patch ids of the input faces: the library's segmentation when known, else the preview's. */
export function patchOfFace(): Uint32Array | undefined {
  return page.libraryPatchOfFace ?? page.input?.preview.patchOfFace;
}

/** The patch of input face f (undefined: none, e.g. a face the library's repair dropped). */
export function inputPatch(f: number): number | undefined {
  const p = patchOfFace()?.[f];
  return p === undefined || p === NO_PATCH ? undefined : p;
}

export function featureEdges(): Uint32Array | undefined {
  return page.output?.result.inputFeatureEdges ?? page.input?.preview.featureEdges;
}

/** Positions (3 per corner) of the exempt corners' vertices in a mesh. */
export function cornerPositions(mesh: Mesh3, which: 'vertex' | 'outputVertex'): Float64Array {
  return exemptCornerPositions(mesh.positions, page.output?.result.report.exemptCorners ?? [], which);
}

export function notice(text: string | undefined): void {
  noticeBox.hidden = !text;
  noticeBox.textContent = text ?? '';
  noticeBox.title = text ?? ''; // one line shown: the whole text on hover
}

export function updateButtons(): void {
  const rb = $<HTMLButtonElement>('#remesh-button');
  rb.disabled = !page.input || !engine.canRemesh || !!page.running;
  rb.title = engine.canRemesh ? '' : 'remesh is not available in this build of conformesh';
  $<HTMLButtonElement>('#cancel-button').disabled = !page.running;
  $<HTMLButtonElement>('#download-report').disabled = !page.output;
  for (const b of document.querySelectorAll<HTMLButtonElement>('#export button[data-format]')) {
    const f = b.dataset.format;
    b.disabled = !page.output || (f === 'obj-uv' && !page.output.atlas);
    b.title = f === 'obj-uv' && page.output && !page.output.atlas ? 'this remesh result carries no planar patches to make UVs from' : '';
  }
}
