// Loading a mesh (a file, a dropped file or a sample): read, analyse, show; flatten a disk-like input.
import type { MeshInfo } from 'conformesh';
import type { Mesh3 } from './engine.ts';
import { clearError, readable, showError } from './errors.ts';
import { mountingPlateOff } from './plate.ts';
import { $, analyzer, engine, errorBox, lastLoad, notice, page, params, progress, setState, updateButtons } from './page.ts';
import { buildFlat, buildInput, rebuildAll } from './page-views.ts';
import annulusUrl from '../samples/annulus.ply?url';
import boxWithHoleUrl from '../samples/box-with-hole.stl?url';
import diskUrl from '../samples/disk.obj?url';
import needsRepairUrl from '../samples/needs-repair.obj?url';
import torusUrl from '../samples/torus.off?url';

export async function load(bytes: Uint8Array, name: string): Promise<void> {
  const seq = ++page.loadSeq;
  page.running?.abort();
  clearError(errorBox);
  notice(undefined);
  setState('loading');
  $('#mesh-name').textContent = `reading ${name} (${(bytes.length / 1024).toFixed(0)} KB)…`;
  try {
    const read = await engine.read(bytes, name);
    if (seq !== page.loadSeq) return;
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
    if (seq !== page.loadSeq) return;
    const tGeo = performance.now();
    const a = await analyzer.analyze(mesh, { angles: true, featureAngle: params.featureAngle });
    if (seq !== page.loadSeq) return;
    page.input = {
      name,
      mesh,
      bounds: a.bounds,
      angles: a.angles!,
      stats: a.stats!,
      preview: a.preview!,
      ...(info ? { info } : {}),
    };
    page.output = undefined;
    page.flatPatches = undefined;
    page.flatPreviewFailure = undefined;
    page.libraryPatchOfFace = undefined;
    page.selected = undefined;
    $('#mesh-name').textContent = `${name}: ${mesh.positions.length / 3} vertices, ${mesh.triangles.length / 3} triangles` +
      (info ? `, genus ${info.genus}, ${info.boundaryLoops} boundary loops, ${info.components} component(s)` : '') +
      (read.warnings.length ? ` — reader: ${read.warnings.join('; ')}` : '');
    const findings = (info?.warnings ?? []).map((w) => (typeof w === 'string' ? w : (w as { message: string }).message));
    notice(findings.length ? `Topology findings (the remesher repairs or rejects these): ${findings.join('; ')}` : undefined);
    progress.reset();
    progress.endRunStatus('');
    const tBuild = performance.now();
    buildInput(true);
    rebuildAll();
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
    if (seq !== page.loadSeq) return;
    showError(errorBox, e, `reading ${name}`);
    $('#mesh-name').textContent = page.input ? `still showing ${page.input.name}` : '';
    setState('error');
  }
}

async function flattenInput(seq: number): Promise<void> {
  if (!page.input) return;
  const ac = new AbortController();
  try {
    const r = await engine.flatten(page.input.mesh, params, page.input.bounds.diagonal, ac.signal);
    if (seq !== page.loadSeq || page.output) return;
    page.flatPatches = r.patches;
    if (r.inputPatchOfFace) page.libraryPatchOfFace = r.inputPatchOfFace;
    buildInput(false);
    buildFlat();
  } catch (e) {
    if (seq !== page.loadSeq) return;
    // a preview the user did not ask for: said in the flat view, not as an error of the page
    const r = readable(e);
    page.flatPreviewFailure =
      `The input could not be flattened in one piece (${r.code}: ${r.message}). ` +
      'Run Remesh to see every patch flattened: it cuts the surface into patches first.';
    buildFlat();
  }
}

export async function loadFile(file: File): Promise<void> {
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

export async function loadSample(which: string): Promise<void> {
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
