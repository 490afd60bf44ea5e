// The three views (input, flattened patches, remesh), what they show and the selection of a
// patch across them; and the panels under them (quality table, histogram, exempt corners).
import type { LineSegments, Mesh, Points } from 'three';
import { showError } from './errors.ts';
import { drawHistogram } from './histogram.ts';
import { reportValues, type Value } from './quality.ts';
import { renderExemptList, renderQualityTable } from './report-panel.ts';
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
import { $, CORNER_COLOR, cornerPositions, engine, errorBox, featureEdges, inputPatch, page, params, patchOfFace, toggles } from './page.ts';

export const inputView = new Viewport($('[data-testid=canvas-input]'), '3d');
export const flatView = new Viewport($('[data-testid=canvas-flat]'), '2d');
export const remeshView = new Viewport($('[data-testid=canvas-remesh]'), '3d');
export const views = [inputView, flatView, remeshView];
for (const v of views) {
  v.warmUp(materialSamples(v.mode)).catch((e) => showError(errorBox, e, 'compiling the views\u2019 shaders'));
}

/** The objects in the views' scenes (undefined: not built). */
export const scene = {
  inputMesh: undefined as Mesh | undefined,
  inputTextured: undefined as Mesh | undefined,
  remeshTextured: undefined as Mesh | undefined,
  inputFeatures: undefined as LineSegments | undefined,
  inputWire: undefined as LineSegments | undefined,
  flat: undefined as FlatScene | undefined,
  remeshMesh: undefined as Mesh | undefined,
  remeshWire: undefined as LineSegments | undefined,
  inputCorners: undefined as Points | undefined,
  remeshCorners: undefined as Points | undefined,
};

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

export function legend(): void {
  legendText();
  // a legend is clamped to three lines: the whole text on hover
  for (const id of ['#legend-input', '#legend-flat', '#legend-remesh']) $(id).title = $(id).textContent ?? '';
}

function legendText(): void {
  const li = $('#legend-input');
  const lf = $('#legend-flat');
  const lr = $('#legend-remesh');
  if (!page.input) {
    li.textContent = 'load a mesh';
    lf.textContent = '';
    lr.textContent = '';
    return;
  }
  const pid = patchOfFace();
  const source = page.libraryPatchOfFace
    ? 'the library\u2019s segmentation, as in views 2 and 3'
    : `preview: regions between edges sharper than ${params.featureAngle}° (Remesh shows the library\u2019s patches)`;
  const corners = page.output?.result.report.exemptCorners.length;
  const cornerText = corners ? ` · magenta dots: ${corners} exempt corner${corners === 1 ? '' : 's'}` : '';
  li.textContent = `${page.input.name} · ${page.input.mesh.triangles.length / 3} triangles · orange: feature curves · colours: patches (${source})${cornerText}` +
    (page.selected !== undefined && pid ? ` · selected patch ${page.selected}` : '');
  if (scene.flat) {
    const [a, b] = scene.flat.factorRange;
    const fill = !scene.flat.hasFactor
      ? 'fill: patch colours'
      : b - a > 1e-9
        ? `fill: conformal factor u, ${a.toFixed(2)} (dark) … ${b.toFixed(2)} (yellow)`
        : `fill: conformal factor u = ${a.toFixed(2)} everywhere (the map is an isometry: the patch is flat)`;
    lf.textContent = `${scene.flat.fills.length} patches · ${fill} · white: input layout · orange: refined mesh` +
      (page.selected !== undefined ? ` · selected patch ${page.selected}` : '');
  } else lf.textContent = '';
  lr.textContent = page.output
    ? `${page.output.result.mesh.triangles.length / 3} triangles · triangle min angle: red < 20°, orange < 30°, green ≥ 30° (brighter toward 60°)${cornerText}` +
      (page.selected !== undefined && page.output.result.patchOfTriangle ? ` · selected patch ${page.selected}` : '')
    : '';
}

export function paintInput(): void {
  if (!page.input || !scene.inputMesh) return;
  paintFaces(scene.inputMesh, (f) => {
    const p = inputPatch(f);
    const base = toggles.patches && p !== undefined ? patchColor(p) : NEUTRAL;
    return selectionShade(base, p, page.selected);
  });
  inputView.requestRender();
}

/**
 * The checker-textured copy of a view's mesh (built on first use) shown instead of its coloured
 * faces while the view's "checker uv" toggle is on; the toggle is off and disabled without uvs.
 */
export function showTexture(which: 'input' | 'remesh'): void {
  const view = which === 'input' ? inputView : remeshView;
  const mesh = which === 'input' ? page.input?.mesh : page.output?.result.mesh;
  const faces = which === 'input' ? scene.inputMesh : scene.remeshMesh;
  const box = $<HTMLInputElement>(which === 'input' ? '#show-input-texture' : '#show-remesh-texture');
  const key = which === 'input' ? 'inputTexture' : 'remeshTexture';
  box.disabled = !mesh || !hasUv(mesh);
  const on = toggles[key] && !box.disabled;
  let textured = which === 'input' ? scene.inputTextured : scene.remeshTextured;
  if (on && !textured && mesh) {
    textured = texturedMesh(mesh);
    view.scene.add(textured);
    if (which === 'input') scene.inputTextured = textured;
    else scene.remeshTextured = textured;
  }
  if (textured) textured.visible = on;
  if (faces) faces.visible = !on;
  view.requestRender();
}

export function buildInput(frame: boolean): void {
  inputView.clear();
  scene.inputMesh = scene.inputFeatures = scene.inputWire = scene.inputTextured = undefined;
  if (!page.input) return;
  scene.inputMesh = faceColoredMesh(page.input.mesh);
  inputView.scene.add(scene.inputMesh);
  inputView.pickable = [scene.inputMesh];
  const fe = featureEdges();
  if (fe && fe.length) {
    scene.inputFeatures = edgeLines(page.input.mesh.positions, fe, 0xff8c1a);
    scene.inputFeatures.visible = toggles.features;
    inputView.scene.add(scene.inputFeatures);
  }
  if (toggles.inputWire) ensureInputWire();
  scene.inputCorners = undefined;
  placeInputCorners();
  paintInput();
  showTexture('input');
  if (frame) inputView.frame([scene.inputMesh]);
  inputView.requestRender();
}

/** After a remesh: the input mesh stays, its patch colours change (rebuilt only when the result brings its own feature curves). */
export function refreshInput(): void {
  if (!scene.inputMesh || page.output?.result.inputFeatureEdges) buildInput(false);
  else {
    placeInputCorners();
    paintInput();
  }
}

/** Dots on the input's exempt corners (the last remesh's report), replacing earlier ones. */
function placeInputCorners(): void {
  if (scene.inputCorners) {
    inputView.scene.remove(scene.inputCorners);
    scene.inputCorners.geometry.dispose();
    scene.inputCorners = undefined;
  }
  if (!page.input || !page.output?.result.report.exemptCorners.length) return;
  scene.inputCorners = cornerMarkers(cornerPositions(page.input.mesh, 'vertex'), CORNER_COLOR);
  inputView.scene.add(scene.inputCorners);
}

/** The input wireframe is built on first use (it costs as much as the mesh itself). */
export function ensureInputWire(): void {
  if (scene.inputWire || !page.input) return;
  scene.inputWire = wireframe(page.input.mesh, 0x101215, 0.5);
  inputView.scene.add(scene.inputWire);
}

function showUnavailable(id: string, text: string | undefined): void {
  const el = $(id);
  el.hidden = !text;
  el.textContent = text ?? '';
}

export function buildFlat(): void {
  flatView.clear();
  scene.flat = undefined;
  const patches = page.output?.result.patches.length ? page.output.result.patches : page.flatPatches;
  if (!patches || patches.length === 0) {
    if (!engine.canFlatten && !engine.canRemesh) {
      showUnavailable('#flat-unavailable', 'Flattening is not available in this build of conformesh: the package has no flatten/remesh binding yet. Nothing is shown rather than a made-up domain.');
    } else if (page.output) {
      showUnavailable('#flat-unavailable', 'This build\u2019s remesh result carries no planar patches to show.');
    } else {
      showUnavailable('#flat-unavailable', page.input ? (page.flatPreviewFailure ?? 'Run Remesh to see every patch flattened.') : undefined);
    }
    legend();
    return;
  }
  showUnavailable('#flat-unavailable', undefined);
  scene.flat = flatScene(patches);
  flatView.scene.add(scene.flat.group);
  flatView.pickable = scene.flat.fills;
  for (const l of scene.flat.layoutLines) l.visible = toggles.layout;
  for (const l of scene.flat.refinedLines) l.visible = toggles.refined;
  paintFlat(scene.flat, page.selected);
  flatView.frame([scene.flat.group]);
  legend();
}

function paintRemesh(): void {
  if (!page.output || !scene.remeshMesh) return;
  const pot = page.output.result.patchOfTriangle;
  paintFaces(scene.remeshMesh, (f) => selectionShade(minAngleColor(page.output!.minAngles[f]!), pot?.[f], page.selected));
  remeshView.requestRender();
}

/** The remesh wireframe: built after the mesh, in its own task (see remesh()), or on first use. */
export function ensureRemeshWire(): void {
  if (scene.remeshWire || !page.output || !scene.remeshMesh) return;
  scene.remeshWire = wireframe(page.output.result.mesh, 0x0c0e12, 0.55);
  scene.remeshWire.visible = toggles.remeshWire;
  remeshView.scene.add(scene.remeshWire);
  remeshView.requestRender();
}

export function buildRemesh(): void {
  remeshView.clear();
  scene.remeshMesh = scene.remeshWire = scene.remeshCorners = scene.remeshTextured = undefined;
  showTexture('remesh');
  if (!engine.canRemesh) {
    showUnavailable('#remesh-unavailable', 'Remeshing is not available in this build of conformesh: the package has no remesh binding yet. The Remesh button is disabled; nothing is faked here.');
    return;
  }
  if (!page.output) {
    showUnavailable('#remesh-unavailable', page.input ? 'Press Remesh.' : undefined);
    return;
  }
  showUnavailable('#remesh-unavailable', undefined);
  scene.remeshMesh = faceColoredMesh(page.output.result.mesh);
  remeshView.scene.add(scene.remeshMesh);
  remeshView.pickable = [scene.remeshMesh];
  scene.remeshCorners = undefined;
  if (page.output.result.report.exemptCorners.length) {
    scene.remeshCorners = cornerMarkers(cornerPositions(page.output.result.mesh, 'outputVertex'), CORNER_COLOR);
    remeshView.scene.add(scene.remeshCorners);
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
  page.selected = patch;
  paintInput();
  if (scene.flat) {
    paintFlat(scene.flat, page.selected);
    flatView.requestRender();
  }
  paintRemesh();
  legend();
}

inputView.onPick = (hit) => select(hit ? inputPatch(hit.faceIndex) : undefined);
flatView.onPick = (hit) => select(hit ? (hit.object.userData.patch as number) : undefined);
remeshView.onPick = (hit) => {
  const pot = page.output?.result.patchOfTriangle;
  select(hit && pot ? pot[hit.faceIndex] : undefined);
};

/**
 * What each view highlights (for the end-to-end test): the input faces and remesh triangles drawn
 * bright (a dimmed colour is 0.35 x its base, so no channel exceeds 0.35; a highlighted one is
 * 0.35 + 0.65 x base, above 0.5 for every patch and angle colour), the flattened patches drawn at
 * full colour; and, from the library's result itself, the input faces and output triangles of
 * the selected patch.
 */
export function selectionState() {
  const brightFaces = (m: Mesh | undefined) => {
    const out: number[] = [];
    if (!m) return out;
    const c = m.geometry.getAttribute('color').array as Float32Array;
    for (let f = 0; 9 * f < c.length; ++f) if (Math.max(c[9 * f]!, c[9 * f + 1]!, c[9 * f + 2]!) > 0.5) out.push(f);
    return out;
  };
  const flatBright = (scene.flat?.fills ?? [])
    .filter((fill) => {
      const c = fill.geometry.getAttribute('color').array as Float32Array;
      const base = fill.geometry.userData.baseColors as Float32Array;
      return c.every((x, i) => x === base[i]);
    })
    .map((fill) => fill.userData.patch as number);
  const patch = page.selected === undefined ? undefined : page.output?.result.patches.find((p) => p.id === page.selected);
  const pot = page.output?.result.patchOfTriangle;
  return {
    selected: page.selected,
    input: brightFaces(scene.inputMesh),
    flat: flatBright,
    remesh: brightFaces(scene.remeshMesh),
    library: {
      inputFaces: patch?.layout?.inputFace ? [...new Set(patch.layout.inputFace)].sort((a, b) => a - b) : undefined,
      triangles: pot && page.selected !== undefined ? [...pot.keys()].filter((t) => pot[t] === page.selected) : undefined,
    },
  };
}

// the panels under the views
/** The values the table shows, by the keys of its one table (quality.ts QUALITY). */
function qualityValues(): Map<string, Value> {
  const v = new Map<string, Value>();
  if (page.input) {
    v.set('input.vertices', page.input.mesh.positions.length / 3);
    v.set('input.triangles', page.input.mesh.triangles.length / 3);
    v.set('input.minAngle', page.input.stats.min);
    v.set('input.maxAngle', page.input.stats.max);
    v.set('input.meanMin', page.input.stats.meanMin);
    v.set('input.below30', page.input.stats.below30);
    v.set('input.below20', page.input.stats.below20);
    if (page.input.info) {
      v.set('input.components', page.input.info.components);
      v.set('input.genus', page.input.info.genus);
      v.set('input.boundaryLoops', page.input.info.boundaryLoops);
    }
  }
  if (page.output) {
    for (const [k, x] of reportValues(page.output.result.report)) v.set(k, x);
    v.set('page.seconds', page.output.seconds);
  }
  return v;
}

export function qualityTable(): void {
  renderQualityTable($('#quality'), qualityValues(), page.output?.bound ?? params.minAngle);
}

export function histogram(): void {
  drawHistogram($<HTMLCanvasElement>('#histogram'), page.input?.angles, page.output?.angles, params.minAngle);
}

export function exemptList(): void {
  renderExemptList($('#exempt-corners'), $('#exempt-note'), page.output?.result.report.exemptCorners, page.output?.bound ?? params.minAngle, !!page.input);
}

/** The flat and remesh views and every panel, rebuilt from the state (at start and after a load). */
export function rebuildAll(): void {
  buildFlat();
  buildRemesh();
  qualityTable();
  exemptList();
  histogram();
  legend();
}
