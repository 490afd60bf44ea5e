// The conformesh demo page: load a mesh, remesh it in a Web Worker, show the input (features,
// patches), the flattened domain and the remesh side by side, with the quality report and exports.
import GUI from 'lil-gui';
import type { LineSegments, Mesh, Points } from 'three';
import type { MeshInfo, RemeshReport } from 'conformesh';
import { Engine, NO_PATCH, type FlatPatch, type Mesh3, type Params, type RemeshOutput } from './engine.ts';
import { objWithUvs, uvAtlas, type UvAtlas } from './atlas.ts';
import { clearError, showError } from './errors.ts';
import { Analyzer } from './analysis.ts';
import { minAnglePerTriangle, type AngleStats, type Bounds, type FeaturePreview } from './geometry.ts';
import { drawHistogram } from './histogram.ts';
import { mountingPlateOff } from './plate.ts';
import { FrameProbe } from './probe.ts';
import { reportedStages, reportValues, type Value } from './quality.ts';
import { ProgressPanel } from './progress-panel.ts';
import { exemptCornerPositions, renderExemptList, renderQualityTable } from './report-panel.ts';
import {
  NEUTRAL,
  cornerMarkers,
  edgeLines,
  faceColoredMesh,
  flatScene,
  hasUv,
  materialSamples,
  minAngleColor,
  paintFaces,
  paintFlat,
  patchColor,
  selectionShade,
  texturedMesh,
  wireframe,
  type FlatScene,
} from './scenes.ts';
import { Viewport } from './viewport.ts';
import annulusUrl from '../samples/annulus.ply?url';
import boxWithHoleUrl from '../samples/box-with-hole.stl?url';
import diskUrl from '../samples/disk.obj?url';
import needsRepairUrl from '../samples/needs-repair.obj?url';
import torusUrl from '../samples/torus.off?url';

const $ = <T extends HTMLElement = HTMLElement>(sel: string) => document.querySelector<T>(sel)!;
const errorBox = $('#error');
const noticeBox = $('#notice');
const loadPanel = $('#load');
const probe = new FrameProbe();
const analyzer = new Analyzer();

// ---------------------------------------------------------------- state
interface Input {
  name: string;
  mesh: Mesh3;
  bounds: Bounds;
  angles: Float64Array;
  stats: AngleStats;
  info?: MeshInfo;
  preview: FeaturePreview;
}
interface Output {
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
let input: Input | undefined;
let output: Output | undefined;
let flatPatches: FlatPatch[] | undefined;
let libraryPatchOfFace: Uint32Array | undefined;
let selected: number | undefined;
let running: AbortController | undefined;
let loadSeq = 0;
const lastLoad = { analysisMs: NaN, buildMs: NaN, firstFrameMs: NaN };
/** The last remesh: the page probe's worst frame gap, and performance.now() at the click, the result's arrival and the end of its application. */
const lastRemesh = {
  maxFrameGapMs: NaN, maxFrameGapEndMs: NaN, frames: 0, seconds: NaN, applyMs: NaN, startAt: NaN, resultAt: NaN, appliedAt: NaN,
  /** Main-thread time of each step of the result's application (ms). */
  applySteps: {} as Record<string, number>,
};

const params: Params = { minAngle: 30, edgeLength: 0.02, featureAngle: 40, chordTolerance: 0.001, boundary: 'free' };
const toggles = {
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
const CORNER_COLOR = 0xff3df0;

function setState(s: string): void {
  document.body.dataset.state = s;
}

// ---------------------------------------------------------------- engine
let engine: Engine;
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

// ---------------------------------------------------------------- views
const inputView = new Viewport($('[data-testid=canvas-input]'), '3d');
const flatView = new Viewport($('[data-testid=canvas-flat]'), '2d');
const remeshView = new Viewport($('[data-testid=canvas-remesh]'), '3d');
const views = [inputView, flatView, remeshView];
for (const v of views) {
  v.warmUp(materialSamples(v.mode)).catch((e) => showError(errorBox, e, 'compiling the views\u2019 shaders'));
}

let inputMesh: Mesh | undefined;
let inputTextured: Mesh | undefined;
let remeshTextured: Mesh | undefined;
let inputFeatures: LineSegments | undefined;
let inputWire: LineSegments | undefined;
let flat: FlatScene | undefined;
let remeshMesh: Mesh | undefined;
let remeshWire: LineSegments | undefined;
let inputCorners: Points | undefined;
let remeshCorners: Points | undefined;

// the two 3D views share their camera
let syncing = false;
function linkCameras(a: Viewport, b: Viewport): void {
  a.controls.addEventListener('change', () => {
    if (syncing) return;
    syncing = true;
    b.camera.position.copy(a.camera.position);
    b.controls.target.copy(a.controls.target);
    b.controls.update();
    b.requestRender();
    syncing = false;
  });
}
linkCameras(inputView, remeshView);
linkCameras(remeshView, inputView);

/** Patch ids of the input faces: the library's segmentation when known, else the preview's. */
function patchOfFace(): Uint32Array | undefined {
  return libraryPatchOfFace ?? input?.preview.patchOfFace;
}

/** The patch of input face f (undefined: none, e.g. a face the library's repair dropped). */
function inputPatch(f: number): number | undefined {
  const p = patchOfFace()?.[f];
  return p === undefined || p === NO_PATCH ? undefined : p;
}

function featureEdges(): Uint32Array | undefined {
  return output?.result.inputFeatureEdges ?? input?.preview.featureEdges;
}

function legend(): void {
  legendText();
  // a legend is clamped to three lines: the whole text on hover
  for (const id of ['#legend-input', '#legend-flat', '#legend-remesh']) $(id).title = $(id).textContent ?? '';
}

function legendText(): void {
  const li = $('#legend-input');
  const lf = $('#legend-flat');
  const lr = $('#legend-remesh');
  if (!input) {
    li.textContent = 'load a mesh';
    lf.textContent = '';
    lr.textContent = '';
    return;
  }
  const pid = patchOfFace();
  const source = libraryPatchOfFace
    ? 'the library\u2019s segmentation, as in views 2 and 3'
    : `preview: regions between edges sharper than ${params.featureAngle}° (Remesh shows the library\u2019s patches)`;
  const corners = output?.result.report.exemptCorners.length;
  const cornerText = corners ? ` · magenta dots: ${corners} exempt corner${corners === 1 ? '' : 's'}` : '';
  li.textContent = `${input.name} · ${input.mesh.triangles.length / 3} triangles · orange: feature curves · colours: patches (${source})${cornerText}` +
    (selected !== undefined && pid ? ` · selected patch ${selected}` : '');
  if (flat) {
    const [a, b] = flat.factorRange;
    const fill = !flat.hasFactor
      ? 'fill: patch colours'
      : b - a > 1e-9
        ? `fill: conformal factor u, ${a.toFixed(2)} (dark) … ${b.toFixed(2)} (yellow)`
        : `fill: conformal factor u = ${a.toFixed(2)} everywhere (the map is an isometry: the patch is flat)`;
    lf.textContent = `${flat.fills.length} patches · ${fill} · white: input layout · orange: refined mesh` +
      (selected !== undefined ? ` · selected patch ${selected}` : '');
  } else lf.textContent = '';
  lr.textContent = output
    ? `${output.result.mesh.triangles.length / 3} triangles · triangle min angle: red < 20°, orange < 30°, green ≥ 30° (brighter toward 60°)${cornerText}` +
      (selected !== undefined && output.result.patchOfTriangle ? ` · selected patch ${selected}` : '')
    : '';
}

function paintInput(): void {
  if (!input || !inputMesh) return;
  paintFaces(inputMesh, (f) => {
    const p = inputPatch(f);
    const base = toggles.patches && p !== undefined ? patchColor(p) : NEUTRAL;
    return selectionShade(base, p, selected);
  });
  inputView.requestRender();
}

/**
 * The checker-textured copy of a view's mesh (built on first use) shown instead of its coloured
 * faces while the view's "checker uv" toggle is on; the toggle is off and disabled without uvs.
 */
function showTexture(which: 'input' | 'remesh'): void {
  const view = which === 'input' ? inputView : remeshView;
  const mesh = which === 'input' ? input?.mesh : output?.result.mesh;
  const faces = which === 'input' ? inputMesh : remeshMesh;
  const box = $<HTMLInputElement>(which === 'input' ? '#show-input-texture' : '#show-remesh-texture');
  const key = which === 'input' ? 'inputTexture' : 'remeshTexture';
  box.disabled = !mesh || !hasUv(mesh);
  const on = toggles[key] && !box.disabled;
  let textured = which === 'input' ? inputTextured : remeshTextured;
  if (on && !textured && mesh) {
    textured = texturedMesh(mesh);
    view.scene.add(textured);
    if (which === 'input') inputTextured = textured;
    else remeshTextured = textured;
  }
  if (textured) textured.visible = on;
  if (faces) faces.visible = !on;
  view.requestRender();
}

function buildInput(frame: boolean): void {
  inputView.clear();
  inputMesh = inputFeatures = inputWire = inputTextured = undefined;
  if (!input) return;
  inputMesh = faceColoredMesh(input.mesh);
  inputView.scene.add(inputMesh);
  inputView.pickable = [inputMesh];
  const fe = featureEdges();
  if (fe && fe.length) {
    inputFeatures = edgeLines(input.mesh.positions, fe, 0xff8c1a);
    inputFeatures.visible = toggles.features;
    inputView.scene.add(inputFeatures);
  }
  if (toggles.inputWire) ensureInputWire();
  inputCorners = undefined;
  placeInputCorners();
  paintInput();
  showTexture('input');
  if (frame) inputView.frame([inputMesh]);
  inputView.requestRender();
}

/** After a remesh: the input mesh stays, its patch colours change (rebuilt only when the result brings its own feature curves). */
function refreshInput(): void {
  if (!inputMesh || output?.result.inputFeatureEdges) buildInput(false);
  else {
    placeInputCorners();
    paintInput();
  }
}

/** Dots on the input's exempt corners (the last remesh's report), replacing earlier ones. */
function placeInputCorners(): void {
  if (inputCorners) {
    inputView.scene.remove(inputCorners);
    inputCorners.geometry.dispose();
    inputCorners = undefined;
  }
  if (!input || !output?.result.report.exemptCorners.length) return;
  inputCorners = cornerMarkers(cornerPositions(input.mesh, 'vertex'), CORNER_COLOR);
  inputView.scene.add(inputCorners);
}

/** The input wireframe is built on first use (it costs as much as the mesh itself). */
function ensureInputWire(): void {
  if (inputWire || !input) return;
  inputWire = wireframe(input.mesh, 0x101215, 0.5);
  inputView.scene.add(inputWire);
}

function showUnavailable(id: string, text: string | undefined): void {
  const el = $(id);
  el.hidden = !text;
  el.textContent = text ?? '';
}

function buildFlat(): void {
  flatView.clear();
  flat = undefined;
  const patches = output?.result.patches.length ? output.result.patches : flatPatches;
  if (!patches || patches.length === 0) {
    if (!engine.canFlatten && !engine.canRemesh) {
      showUnavailable('#flat-unavailable', 'Flattening is not available in this build of conformesh: the package has no flatten/remesh binding yet. Nothing is shown rather than a made-up domain.');
    } else if (output) {
      showUnavailable('#flat-unavailable', 'This build\u2019s remesh result carries no planar patches to show.');
    } else {
      showUnavailable('#flat-unavailable', input ? 'Run Remesh to see every patch flattened.' : undefined);
    }
    legend();
    return;
  }
  showUnavailable('#flat-unavailable', undefined);
  flat = flatScene(patches);
  flatView.scene.add(flat.group);
  flatView.pickable = flat.fills;
  for (const l of flat.layoutLines) l.visible = toggles.layout;
  for (const l of flat.refinedLines) l.visible = toggles.refined;
  paintFlat(flat, selected);
  flatView.frame([flat.group]);
  legend();
}

function paintRemesh(): void {
  if (!output || !remeshMesh) return;
  const pot = output.result.patchOfTriangle;
  paintFaces(remeshMesh, (f) => selectionShade(minAngleColor(output!.minAngles[f]!), pot?.[f], selected));
  remeshView.requestRender();
}

/** The remesh wireframe: built after the mesh, in its own task (see remesh()), or on first use. */
function ensureRemeshWire(): void {
  if (remeshWire || !output || !remeshMesh) return;
  remeshWire = wireframe(output.result.mesh, 0x0c0e12, 0.55);
  remeshWire.visible = toggles.remeshWire;
  remeshView.scene.add(remeshWire);
  remeshView.requestRender();
}

function buildRemesh(): void {
  remeshView.clear();
  remeshMesh = remeshWire = remeshCorners = remeshTextured = undefined;
  showTexture('remesh');
  if (!engine.canRemesh) {
    showUnavailable('#remesh-unavailable', 'Remeshing is not available in this build of conformesh: the package has no remesh binding yet. The Remesh button is disabled; nothing is faked here.');
    return;
  }
  if (!output) {
    showUnavailable('#remesh-unavailable', input ? 'Press Remesh.' : undefined);
    return;
  }
  showUnavailable('#remesh-unavailable', undefined);
  remeshMesh = faceColoredMesh(output.result.mesh);
  remeshView.scene.add(remeshMesh);
  remeshView.pickable = [remeshMesh];
  remeshCorners = undefined;
  if (output.result.report.exemptCorners.length) {
    remeshCorners = cornerMarkers(cornerPositions(output.result.mesh, 'outputVertex'), CORNER_COLOR);
    remeshView.scene.add(remeshCorners);
  }
  paintRemesh();
  showTexture('remesh');
  // same camera as the input view
  remeshView.camera.position.copy(inputView.camera.position);
  remeshView.controls.target.copy(inputView.controls.target);
  (remeshView.camera as typeof inputView.camera).near = (inputView.camera as typeof remeshView.camera).near;
  remeshView.camera.far = inputView.camera.far;
  remeshView.camera.updateProjectionMatrix();
  remeshView.controls.update();
  remeshView.requestRender();
}

function select(patch: number | undefined): void {
  selected = patch;
  paintInput();
  if (flat) {
    paintFlat(flat, selected);
    flatView.requestRender();
  }
  paintRemesh();
  legend();
}

inputView.onPick = (hit) => select(hit ? inputPatch(hit.faceIndex) : undefined);
flatView.onPick = (hit) => select(hit ? (hit.object.userData.patch as number) : undefined);
remeshView.onPick = (hit) => {
  const pot = output?.result.patchOfTriangle;
  select(hit && pot ? pot[hit.faceIndex] : undefined);
};

/**
 * What each view highlights (for the end-to-end test): the input faces and remesh triangles drawn
 * bright (a dimmed colour is 0.35 x its base, so no channel exceeds 0.35; a highlighted one is
 * 0.35 + 0.65 x base, above 0.5 for every patch and angle colour), the flattened patches drawn at
 * full colour; and, from the library's result itself, the input faces and output triangles of
 * the selected patch.
 */
function selectionState() {
  const brightFaces = (m: Mesh | undefined) => {
    const out: number[] = [];
    if (!m) return out;
    const c = m.geometry.getAttribute('color').array as Float32Array;
    for (let f = 0; 9 * f < c.length; ++f) if (Math.max(c[9 * f]!, c[9 * f + 1]!, c[9 * f + 2]!) > 0.5) out.push(f);
    return out;
  };
  const flatBright = (flat?.fills ?? [])
    .filter((fill) => {
      const c = fill.geometry.getAttribute('color').array as Float32Array;
      const base = fill.geometry.userData.baseColors as Float32Array;
      return c.every((x, i) => x === base[i]);
    })
    .map((fill) => fill.userData.patch as number);
  const patch = selected === undefined ? undefined : output?.result.patches.find((p) => p.id === selected);
  const pot = output?.result.patchOfTriangle;
  return {
    selected,
    input: brightFaces(inputMesh),
    flat: flatBright,
    remesh: brightFaces(remeshMesh),
    library: {
      inputFaces: patch?.layout?.inputFace ? [...new Set(patch.layout.inputFace)].sort((a, b) => a - b) : undefined,
      triangles: pot && selected !== undefined ? [...pot.keys()].filter((t) => pot[t] === selected) : undefined,
    },
  };
}

// ---------------------------------------------------------------- quality panel
/** The values the table shows, by the keys of its one table (quality.ts QUALITY). */
function qualityValues(): Map<string, Value> {
  const v = new Map<string, Value>();
  if (input) {
    v.set('input.vertices', input.mesh.positions.length / 3);
    v.set('input.triangles', input.mesh.triangles.length / 3);
    v.set('input.minAngle', input.stats.min);
    v.set('input.maxAngle', input.stats.max);
    v.set('input.meanMin', input.stats.meanMin);
    v.set('input.below30', input.stats.below30);
    v.set('input.below20', input.stats.below20);
    if (input.info) {
      v.set('input.components', input.info.components);
      v.set('input.genus', input.info.genus);
      v.set('input.boundaryLoops', input.info.boundaryLoops);
    }
  }
  if (output) {
    for (const [k, x] of reportValues(output.result.report)) v.set(k, x);
    v.set('page.seconds', output.seconds);
  }
  return v;
}

function qualityTable(): void {
  renderQualityTable($('#quality'), qualityValues(), output?.bound ?? params.minAngle);
}

function histogram(): void {
  drawHistogram($<HTMLCanvasElement>('#histogram'), input?.angles, output?.angles, params.minAngle);
}

// ---------------------------------------------------------------- exempt corners
function exemptList(): void {
  renderExemptList($('#exempt-corners'), $('#exempt-note'), output?.result.report.exemptCorners, output?.bound ?? params.minAngle, !!input);
}

/** Positions (3 per corner) of the exempt corners' vertices in a mesh. */
function cornerPositions(mesh: Mesh3, which: 'vertex' | 'outputVertex'): Float64Array {
  return exemptCornerPositions(mesh.positions, output?.result.report.exemptCorners ?? [], which);
}

// ---------------------------------------------------------------- progress
const progress = new ProgressPanel($('#progress'), $('#run-status'), () => !!running);

// ---------------------------------------------------------------- loading
function notice(text: string | undefined): void {
  noticeBox.hidden = !text;
  noticeBox.textContent = text ?? '';
  noticeBox.title = text ?? ''; // one line shown: the whole text on hover
}

function updateButtons(): void {
  const rb = $<HTMLButtonElement>('#remesh-button');
  rb.disabled = !input || !engine.canRemesh || !!running;
  rb.title = engine.canRemesh ? '' : 'remesh is not available in this build of conformesh';
  $<HTMLButtonElement>('#cancel-button').disabled = !running;
  $<HTMLButtonElement>('#download-report').disabled = !output;
  for (const b of document.querySelectorAll<HTMLButtonElement>('#export button[data-format]')) {
    const f = b.dataset.format;
    b.disabled = !output || (f === 'obj-uv' && !output.atlas);
    b.title = f === 'obj-uv' && output && !output.atlas ? 'this remesh result carries no planar patches to make UVs from' : '';
  }
}

async function load(bytes: Uint8Array, name: string): Promise<void> {
  const seq = ++loadSeq;
  running?.abort();
  clearError(errorBox);
  notice(undefined);
  setState('loading');
  $('#mesh-name').textContent = `reading ${name} (${(bytes.length / 1024).toFixed(0)} KB)…`;
  try {
    const read = await engine.read(bytes, name);
    if (seq !== loadSeq) return;
    // the file's uvs and attributes go to the remesh, which carries them over (checker uv toggles)
    const mesh: Mesh3 = { positions: read.positions, triangles: read.triangles };
    if (read.uvs) mesh.uvs = read.uvs;
    if (read.attributes) mesh.attributes = read.attributes;
    let info: MeshInfo | undefined;
    try {
      info = await engine.info(mesh);
    } catch (e) {
      // a build without the topology report still shows the mesh; anything else is a real error
      if (!(e instanceof Error && /has no 'meshInfo'/.test(e.message))) throw e;
    }
    if (seq !== loadSeq) return;
    const tGeo = performance.now();
    const a = await analyzer.analyze(mesh, { angles: true, featureAngle: params.featureAngle });
    if (seq !== loadSeq) return;
    input = {
      name,
      mesh,
      bounds: a.bounds,
      angles: a.angles!,
      stats: a.stats!,
      preview: a.preview!,
      ...(info ? { info } : {}),
    };
    output = undefined;
    flatPatches = undefined;
    libraryPatchOfFace = undefined;
    selected = undefined;
    $('#mesh-name').textContent = `${name}: ${mesh.positions.length / 3} vertices, ${mesh.triangles.length / 3} triangles` +
      (info ? `, genus ${info.genus}, ${info.boundaryLoops} boundary loops, ${info.components} component(s)` : '') +
      (read.warnings.length ? ` — reader: ${read.warnings.join('; ')}` : '');
    const findings = (info?.warnings ?? []).map((w) => (typeof w === 'string' ? w : (w as { message: string }).message));
    notice(findings.length ? `Topology findings (the remesher repairs or rejects these): ${findings.join('; ')}` : undefined);
    progress.reset();
    progress.endRunStatus('');
    const tBuild = performance.now();
    buildInput(true);
    buildFlat();
    buildRemesh();
    qualityTable();
    exemptList();
    histogram();
    legend();
    updateButtons();
    const tEnd = performance.now();
    requestAnimationFrame(() => {
      const tFrame = performance.now();
      Object.assign(lastLoad, { analysisMs: tBuild - tGeo, buildMs: tEnd - tBuild, firstFrameMs: tFrame - tEnd });
    });
    setState('loaded');
    // flatten() maps one disk-like patch; other inputs get their patches' domains from Remesh
    const disk = info && info.components === 1 && info.boundaryLoops >= 1 && info.genus === 0 && info.nonManifoldEdges === 0;
    if (engine.canFlatten && disk) void flattenInput(seq);
  } catch (e) {
    if (seq !== loadSeq) return;
    showError(errorBox, e, `reading ${name}`);
    $('#mesh-name').textContent = input ? `still showing ${input.name}` : '';
    setState('error');
  }
}

async function flattenInput(seq: number): Promise<void> {
  if (!input) return;
  const ac = new AbortController();
  try {
    const r = await engine.flatten(input.mesh, params, input.bounds.diagonal, ac.signal);
    if (seq !== loadSeq || output) return;
    flatPatches = r.patches;
    if (r.inputPatchOfFace) libraryPatchOfFace = r.inputPatchOfFace;
    buildInput(false);
    buildFlat();
  } catch (e) {
    if (seq !== loadSeq) return;
    showError(errorBox, e, 'flattening the input');
    buildFlat();
  }
}

async function loadFile(file: File): Promise<void> {
  try {
    await load(new Uint8Array(await file.arrayBuffer()), file.name);
  } catch (e) {
    showError(errorBox, e, `reading ${file.name}`);
    setState('error');
  }
}

// meshes made by `conformesh generate` (web/samples/README.md), emitted by Vite as assets
const GENERATED: Record<string, string> = {
  'box-with-hole.stl': boxWithHoleUrl,
  'disk.obj': diskUrl,
  'annulus.ply': annulusUrl,
  'torus.off': torusUrl,
  'needs-repair.obj': needsRepairUrl,
};

async function loadSample(which: string): Promise<void> {
  try {
    const generated = GENERATED[which];
    if (generated) {
      const res = await fetch(generated);
      if (!res.ok) throw new Error(`cannot fetch the sample ${which}: HTTP ${res.status}`);
      await load(new Uint8Array(await res.arrayBuffer()), which);
    } else if (which === 'spot') {
      const res = await fetch('./samples/spot.obj');
      if (!res.ok) throw new Error(`cannot fetch samples/spot.obj: HTTP ${res.status}`);
      await load(new Uint8Array(await res.arrayBuffer()), 'spot.obj');
    } else if (which === 'plate') {
      await load(new TextEncoder().encode(mountingPlateOff()), 'mounting-plate.off');
    }
  } catch (e) {
    showError(errorBox, e, 'loading the sample');
    setState('error');
  }
}

// ---------------------------------------------------------------- remesh
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

async function remesh(): Promise<void> {
  if (!input || running || !engine.canRemesh) return;
  const seq = loadSeq;
  const ac = new AbortController();
  running = ac;
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
    const result = await engine.remesh(input.mesh, params, input.bounds.diagonal, (p) => progress.setProgress(p.stage, p.fraction), ac.signal);
    const resultAt = performance.now();
    const seconds = (resultAt - t0) / 1000;
    const gap = probe.read();
    if (seq !== loadSeq) return;
    progress.finish(result.report);
    progress.endRunStatus(`done in ${seconds.toFixed(2)} s (library ${result.report.seconds.total.toFixed(2)} s)`);
    const a = await analyzer.analyze(result.mesh, { angles: true });
    if (seq !== loadSeq) return;
    const t1 = performance.now();
    let atlas: UvAtlas | undefined;
    try {
      atlas = uvAtlas(result.mesh, result.patches, result.patchOfTriangle);
    } catch (e) {
      // the remesh stands; only the UV export is off (and the page says why)
      showError(errorBox, e, 'building the UV atlas of the remesh');
    }
    output = { result, atlas, angles: a.angles!, minAngles: minAnglePerTriangle(a.angles!), stats: a.stats!, seconds, bound };
    if (result.inputPatchOfFace) libraryPatchOfFace = result.inputPatchOfFace;
    selected = undefined;
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
    if (seq !== loadSeq) return;
    step('flat', buildFlat);
    await drawn(flatView);
    if (seq !== loadSeq) return;
    step('remesh', buildRemesh);
    await drawn(remeshView);
    if (seq !== loadSeq) return;
    step('remeshWire', () => { if (toggles.remeshWire) ensureRemeshWire(); });
    await drawn(remeshView);
    if (seq !== loadSeq) return;
    step('panels', () => { qualityTable(); exemptList(); histogram(); legend(); });
    await Promise.all(views.map((v) => frameOrTimeout(v)));
    if (seq !== loadSeq) return;
    const appliedAt = performance.now();
    Object.assign(lastRemesh, {
      maxFrameGapMs: gap.maxGap, maxFrameGapEndMs: gap.maxGapAt - t0, frames: gap.frames, seconds,
      applyMs: appliedAt - t1, startAt: t0, resultAt, appliedAt, applySteps,
    });
    setState('remeshed');
  } catch (e) {
    if (seq !== loadSeq) return;
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
    if (running === ac) running = undefined;
    holdLoadPanel(false);
    updateButtons();
  }
}

// ---------------------------------------------------------------- export
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
function reportJson(report: RemeshReport): string {
  return JSON.stringify(report, (_k, v: unknown) => (ArrayBuffer.isView(v) ? Array.from(v as unknown as ArrayLike<number>) : v), 2);
}

function downloadReport(): void {
  if (!output || !input) return;
  const base = input.name.replace(/\.[^.]*$/, '') + '-remesh';
  download(new TextEncoder().encode(reportJson(output.result.report) + '\n'), `${base}-report.json`);
}

async function exportAs(format: string): Promise<void> {
  if (!output || !input) return;
  const base = input.name.replace(/\.[^.]*$/, '') + '-remesh';
  const m = output.result.mesh;
  try {
    if (format === 'obj-uv') {
      if (!output.atlas) return;
      const plain = new TextDecoder().decode(await engine.write({ positions: m.positions, triangles: m.triangles }, 'obj'));
      download(new TextEncoder().encode(objWithUvs(plain, m, output.atlas)), `${base}-uv.obj`);
    } else {
      const f = format as 'obj' | 'stl' | 'ply';
      download(await engine.write({ positions: m.positions, triangles: m.triangles }, f), `${base}.${f}`);
    }
  } catch (e) {
    showError(errorBox, e, `writing ${format.toUpperCase()}`);
  }
}

// ---------------------------------------------------------------- controls
const gui = new GUI({ container: $('#params'), title: 'Parameters' });
gui.add(params, 'minAngle', 5, 34, 0.5).name('min angle (°)').onChange(() => { histogram(); qualityTable(); });
gui.add(params, 'edgeLength', 0.002, 0.2, 0.001).name('edge length (× diagonal)');
gui.add(params, 'featureAngle', 5, 120, 1).name('feature angle (°)').onFinishChange(async () => {
  const current = input;
  if (!current || libraryPatchOfFace) return;
  try {
    const a = await analyzer.analyze(current.mesh, { angles: false, featureAngle: params.featureAngle });
    if (current !== input || !a.preview) return;
    current.preview = a.preview;
    selected = undefined;
    buildInput(false);
    legend();
  } catch (e) {
    showError(errorBox, e, 'updating the feature preview');
  }
});
gui.add(params, 'chordTolerance', 0.0001, 0.01, 0.0001).name('chord tolerance (× diag.)');
gui.add(params, 'boundary', { 'free (u = 0)': 'free', 'corner-preserving': 'corners', 'round disk': 'disk' }).name('boundary condition');

$('#remesh-button').addEventListener('click', () => void remesh());
$('#cancel-button').addEventListener('click', () => running?.abort());
for (const b of document.querySelectorAll<HTMLButtonElement>('#export button[data-format]')) {
  b.addEventListener('click', () => void exportAs(b.dataset.format!));
}
$('#download-report').addEventListener('click', downloadReport);
$<HTMLInputElement>('#file-input').addEventListener('change', (e) => {
  const input = e.target as HTMLInputElement;
  const file = input.files?.[0];
  if (file) void loadFile(file);
  input.value = '';
});
$<HTMLSelectElement>('#sample').addEventListener('change', (e) => {
  const v = (e.target as HTMLSelectElement).value;
  if (v) void loadSample(v);
});
const drop = $('#drop');
document.addEventListener('dragover', (e) => {
  e.preventDefault();
  drop.classList.add('over');
});
document.addEventListener('dragleave', (e) => {
  if (e.target === document.documentElement || e.target === drop) drop.classList.remove('over');
});
document.addEventListener('drop', (e) => {
  e.preventDefault();
  drop.classList.remove('over');
  const file = e.dataTransfer?.files?.[0];
  if (file) void loadFile(file);
});
const bindToggle = (id: string, key: keyof typeof toggles, apply: () => void) => {
  const el = $<HTMLInputElement>(id);
  el.checked = toggles[key];
  el.addEventListener('change', () => {
    toggles[key] = el.checked;
    apply();
  });
};
bindToggle('#show-features', 'features', () => { if (inputFeatures) inputFeatures.visible = toggles.features; inputView.requestRender(); });
bindToggle('#show-patches', 'patches', () => paintInput());
bindToggle('#show-input-wire', 'inputWire', () => {
  if (toggles.inputWire) ensureInputWire();
  if (inputWire) inputWire.visible = toggles.inputWire;
  inputView.requestRender();
});
bindToggle('#show-input-texture', 'inputTexture', () => showTexture('input'));
bindToggle('#show-remesh-texture', 'remeshTexture', () => showTexture('remesh'));
bindToggle('#show-layout', 'layout', () => { for (const l of flat?.layoutLines ?? []) l.visible = toggles.layout; flatView.requestRender(); });
bindToggle('#show-refined', 'refined', () => { for (const l of flat?.refinedLines ?? []) l.visible = toggles.refined; flatView.requestRender(); });
bindToggle('#show-remesh-wire', 'remeshWire', () => {
  if (toggles.remeshWire) ensureRemeshWire();
  if (remeshWire) remeshWire.visible = toggles.remeshWire;
  remeshView.requestRender();
});

// nothing escapes as an uncaught exception: show it in the page instead
window.addEventListener('error', (e) => {
  showError(errorBox, e.error ?? e.message, 'unexpected error');
  e.preventDefault();
});
window.addEventListener('unhandledrejection', (e) => {
  showError(errorBox, e.reason, 'unexpected error');
  e.preventDefault();
});

// hooks for the end-to-end test and for scripting the page from the console
declare global {
  interface Window {
    conformeshPage: unknown;
  }
}
window.conformeshPage = {
  probe,
  lastRemesh,
  lastLoad,
  capabilities: { remesh: engine.canRemesh, flatten: engine.canFlatten },
  /** Threads of one remesh in the page's worker (above 1 where the page is cross-origin isolated). */
  remeshThreads: () => engine.remesher.threads(),
  progressLog: progress.log,
  renderAll: () => views.forEach((v) => v.renderNow()),
  loadSample,
  selectionState,
  /** The last remesh's report as the library returned it (typed arrays as arrays), or null. */
  lastReport: () => (output ? (JSON.parse(reportJson(output.result.report)) as unknown) : null),
  /** The exempt-corner dots drawn in the input and remesh views: their positions (3 per dot). */
  cornerDots: () => ({
    input: inputCorners ? Array.from(inputCorners.geometry.getAttribute('position').array) : [],
    remesh: remeshCorners ? Array.from(remeshCorners.geometry.getAttribute('position').array) : [],
    inScene: { input: !!inputCorners?.parent, remesh: !!remeshCorners?.parent },
  }),
};

buildFlat();
buildRemesh();
qualityTable();
exemptList();
histogram();
legend();
updateButtons();
setState('ready');
