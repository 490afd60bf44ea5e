// The conformesh demo page: load a mesh, remesh it in a Web Worker, show the input (features,
// patches), the flattened domain and the remesh side by side, with the quality report and exports.
import GUI from 'lil-gui';
import { showError } from './errors.ts';
import { $, analyzer, errorBox, engine, lastLoad, lastRemesh, page, params, probe, progress, setState, toggles, updateButtons } from './page.ts';
import {
  buildInput, ensureInputWire, ensureRemeshWire, flatView, histogram, inputView, legend, paintInput, qualityTable, rebuildAll,
  remeshView, scene, selectionState, showTexture, views,
} from './page-views.ts';
import { loadFile, loadSample } from './page-load.ts';
import { downloadReport, exportAs, remesh, reportJson } from './page-remesh.ts';

// ---------------------------------------------------------------- controls
const gui = new GUI({ container: $('#params'), title: 'Parameters' });
gui.add(params, 'minAngle', 5, 34, 0.5).name('min angle (°)').onChange(() => { histogram(); qualityTable(); });
gui.add(params, 'edgeLength', 0.002, 0.2, 0.001).name('edge length (× diagonal)');
gui.add(params, 'featureAngle', 5, 120, 1).name('feature angle (°)').onFinishChange(async () => {
  const current = page.input;
  if (!current || page.libraryPatchOfFace) return;
  try {
    const a = await analyzer.analyze(current.mesh, { angles: false, featureAngle: params.featureAngle });
    if (current !== page.input || !a.preview) return;
    current.preview = a.preview;
    page.selected = undefined;
    buildInput(false);
    legend();
  } catch (e) {
    showError(errorBox, e, 'updating the feature preview');
  }
});
gui.add(params, 'chordTolerance', 0.0001, 0.01, 0.0001).name('chord tolerance (× diag.)');
gui.add(params, 'boundary', { 'free (u = 0)': 'free', 'corner-preserving': 'corners', 'round disk': 'disk' }).name('boundary condition');

$('#remesh-button').addEventListener('click', () => void remesh());
$('#cancel-button').addEventListener('click', () => page.running?.abort());
for (const b of document.querySelectorAll<HTMLButtonElement>('#export button[data-format]')) {
  b.addEventListener('click', () => void exportAs(b.dataset.format!));
}
$('#download-report').addEventListener('click', downloadReport);
$<HTMLInputElement>('#file-input').addEventListener('change', (e) => {
  const box = e.target as HTMLInputElement;
  const file = box.files?.[0];
  if (file) void loadFile(file);
  box.value = '';
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
bindToggle('#show-features', 'features', () => { if (scene.inputFeatures) scene.inputFeatures.visible = toggles.features; inputView.requestRender(); });
bindToggle('#show-patches', 'patches', () => paintInput());
bindToggle('#show-input-wire', 'inputWire', () => {
  if (toggles.inputWire) ensureInputWire();
  if (scene.inputWire) scene.inputWire.visible = toggles.inputWire;
  inputView.requestRender();
});
bindToggle('#show-input-texture', 'inputTexture', () => showTexture('input'));
bindToggle('#show-remesh-texture', 'remeshTexture', () => showTexture('remesh'));
bindToggle('#show-layout', 'layout', () => { for (const l of scene.flat?.layoutLines ?? []) l.visible = toggles.layout; flatView.requestRender(); });
bindToggle('#show-refined', 'refined', () => { for (const l of scene.flat?.refinedLines ?? []) l.visible = toggles.refined; flatView.requestRender(); });
bindToggle('#show-remesh-wire', 'remeshWire', () => {
  if (toggles.remeshWire) ensureRemeshWire();
  if (scene.remeshWire) scene.remeshWire.visible = toggles.remeshWire;
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
  lastReport: () => (page.output ? (JSON.parse(reportJson(page.output.result.report)) as unknown) : null),
  /** The exempt-corner dots drawn in the input and remesh views: their positions (3 per dot). */
  cornerDots: () => ({
    input: scene.inputCorners ? Array.from(scene.inputCorners.geometry.getAttribute('position').array) : [],
    remesh: scene.remeshCorners ? Array.from(scene.remeshCorners.geometry.getAttribute('position').array) : [],
    inScene: { input: !!scene.inputCorners?.parent, remesh: !!scene.remeshCorners?.parent },
  }),
};

rebuildAll();
updateButtons();
setState('ready');
