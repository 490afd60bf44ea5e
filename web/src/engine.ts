// The page's access to the library: one createRemesher() worker (the module never runs on the
// main thread), plus the shapes the views need. Functions the package build does not offer yet
// (remesh, flatten) are detected here, so the page can say "not available in this build" rather
// than pretend.
import {
  ConformeshError,
  createRemesher,
  type MeshAttribute,
  type MeshInfo,
  type MeshLike,
  type ReadMeshResult,
  type Remesher,
  type RemeshReport,
} from 'conformesh';
import { mountingPlate } from './plate.ts';

export type BoundaryCondition = 'corners' | 'free' | 'disk';
/** The library's name of the page's boundary condition (the page says 'disk' for the round one). */
const libraryBoundary = (b: BoundaryCondition) => (b === 'disk' ? 'circle' : b);

/** The parameters panel. Lengths are relative to the input's bounding-box diagonal. */
export interface Params {
  minAngle: number;
  edgeLength: number;
  featureAngle: number;
  chordTolerance: number;
  boundary: BoundaryCondition;
}

export interface Mesh3 {
  positions: Float64Array;
  triangles: Uint32Array;
  uvs?: Float64Array;
  /** The file's texture coordinates (per corner at uv seams), normals, colours..., carried through remesh. */
  attributes?: MeshAttribute[];
}

/** One patch of the flattened domain (planar coordinates are per patch). */
export interface FlatPatch {
  id: number;
  /**
   * The input layout: planar positions (2·n) and triangles of the flattened input patch, the log
   * scale factor u per vertex, and the input triangle each layout triangle lies in (several when
   * the library split input triangles before segmenting: mesh/precondition.h).
   */
  layout?: { uv: Float64Array; triangles: Uint32Array; factor?: Float64Array; inputFace?: Uint32Array };
  /**
   * The refined planar mesh (Delaunay refinement output): its triangles are the patch's output
   * triangles in output order, and outputVertex the output vertex of each planar vertex.
   */
  refined?: { uv: Float64Array; triangles: Uint32Array; factor?: Float64Array; outputVertex?: Uint32Array };
}

/** Patch id of an input triangle that no patch covers (e.g. dropped by the library's repair). */
export const NO_PATCH = 0xffffffff;

/**
 * The library's patch of every input triangle, from its patches' layout triangles. A triangle
 * split by the preconditioning may have pieces in several patches (a cut along a new edge): it
 * goes to the patch holding most of its pieces (ties: the lower id). NO_PATCH where none does.
 */
export function patchOfInputFace(patches: FlatPatch[], faceCount: number): Uint32Array {
  const out = new Uint32Array(faceCount).fill(NO_PATCH);
  const pieces = new Uint32Array(faceCount);
  // patches in id order, so that a later patch takes a face only with strictly more pieces
  const byId = [...patches].sort((a, b) => a.id - b.id);
  const count = new Map<number, number>();
  for (const p of byId) {
    const faces = p.layout?.inputFace;
    if (!faces) continue;
    count.clear();
    for (const f of faces) if (f < faceCount) count.set(f, (count.get(f) ?? 0) + 1);
    for (const [f, n] of count) {
      if (out[f] === NO_PATCH || n > pieces[f]!) {
        out[f] = p.id;
        pieces[f] = n;
      }
    }
  }
  return out;
}

export interface RemeshOutput {
  mesh: Mesh3;
  /** The library's quality report, as it returned it. */
  report: RemeshReport;
  /** Patch id of every output triangle, when returned. */
  patchOfTriangle?: Uint32Array;
  /** Patch id of every input triangle (the library's segmentation), when returned. */
  inputPatchOfFace?: Uint32Array;
  /** Feature edges of the input as vertex pairs, when returned. */
  inputFeatureEdges?: Uint32Array;
  patches: FlatPatch[];
}

export interface FlattenOutput {
  patches: FlatPatch[];
  inputPatchOfFace?: Uint32Array;
}

export interface Progress {
  stage: string;
  fraction: number;
}

type Loose = Record<string, unknown>;

function typed<T extends ArrayBufferView>(x: unknown, ctor: { new (a: ArrayLike<number>): T; from(a: ArrayLike<number>): T }): T | undefined {
  if (x === undefined || x === null) return undefined;
  if (x instanceof (ctor as unknown as new () => T)) return x as T;
  if (ArrayBuffer.isView(x) || Array.isArray(x)) return ctor.from(x as ArrayLike<number>);
  return undefined;
}
const f64 = (x: unknown) => typed(x, Float64Array);
const u32 = (x: unknown) => typed(x, Uint32Array);
const pick = (o: Loose | undefined, ...keys: string[]): unknown => {
  if (!o) return undefined;
  for (const k of keys) if (o[k] !== undefined && o[k] !== null) return o[k];
  return undefined;
};

function planar(o: unknown): FlatPatch['layout'] {
  if (!o || typeof o !== 'object') return undefined;
  const r = o as Loose;
  const uv = f64(pick(r, 'uv', 'uvs', 'planar', 'positions2d', 'positions'));
  const triangles = u32(pick(r, 'triangles', 'faces'));
  if (!uv || !triangles) return undefined;
  const out: NonNullable<FlatPatch['refined']> & NonNullable<FlatPatch['layout']> = { uv, triangles };
  const factor = f64(pick(r, 'factor', 'u', 'conformalFactor', 'scale'));
  if (factor) out.factor = factor;
  const inputFace = u32(r.inputFace);
  if (inputFace) out.inputFace = inputFace;
  const outputVertex = u32(r.outputVertex);
  if (outputVertex) out.outputVertex = outputVertex;
  return out;
}

function patchesOf(list: unknown): FlatPatch[] {
  if (!Array.isArray(list)) return [];
  return list.map((p, i) => {
    const r = (p ?? {}) as Loose;
    const id = typeof r.id === 'number' ? r.id : i;
    const out: FlatPatch = { id };
    const layout = planar(pick(r, 'layout', 'input', 'flat')) ?? planar(r);
    const refined = planar(pick(r, 'refined', 'planarMesh', 'output'));
    if (layout) out.layout = layout;
    if (refined) out.refined = refined;
    return out;
  });
}

export class Engine {
  readonly remesher: Remesher;
  readonly canRemesh: boolean;
  readonly canFlatten: boolean;

  constructor() {
    this.remesher = createRemesher({ workers: 1 });
    const r = this.remesher as unknown as Loose;
    this.canRemesh = typeof r.remesh === 'function';
    this.canFlatten = typeof r.flatten === 'function';
  }

  /**
   * Remesh a small generated part once, in the worker, right after start-up. V8 runs new
   * WebAssembly code in its baseline tier and optimizes hot functions in background threads
   * while they run. Without this, the first fandisk remesh after the page loaded had 380-620 ms frame
   * gaps on a 2-core machine; its Chrome trace shows the page's main thread idle through the
   * gap (no frame was scheduled) while two thread-pool threads ran wasm.TopTierCompilation
   * (5.7 s of TurboFan work over the remesh) beside the worker. After this warm-up that
   * remesh's tier-up is ~0.2 s and its gaps stay under 65 ms. The compiled module, optimized
   * code included, is shared with a replacement worker (remesher.ts). Errors are ignored (the
   * real call reports its own). Returns the part's report (the page takes the stages the library
   * reports from it), undefined on failure.
   */
  async warmUp(): Promise<RemeshReport | undefined> {
    if (!this.canRemesh) return undefined;
    const fn = (this.remesher as unknown as Loose).remesh as (m: MeshLike, o: unknown) => Promise<unknown>;
    try {
      const r = (await fn.call(this.remesher, mountingPlate(), { targetEdgeLengthRel: 0.03, computeHausdorff: false })) as Loose;
      return r.report as RemeshReport | undefined;
    } catch {
      // the module failed to load or the part failed: the user's own call will say why
      return undefined;
    }
  }

  version(): Promise<string> {
    return this.remesher.version();
  }

  read(bytes: Uint8Array, fileName: string): Promise<ReadMeshResult> {
    return this.remesher.readMesh(bytes, { fileName });
  }

  info(mesh: MeshLike): Promise<MeshInfo> {
    return this.remesher.meshInfo(mesh);
  }

  write(mesh: MeshLike, format: 'obj' | 'stl' | 'ply', writeUvs = false): Promise<Uint8Array> {
    return this.remesher.writeMesh(mesh, format, { writeUvs });
  }

  /** Library options from the panel's parameters (lengths made absolute with the diagonal). */
  options(params: Params, diagonal: number): Record<string, unknown> {
    return {
      minAngle: params.minAngle,
      targetEdgeLength: params.edgeLength * diagonal,
      featureAngle: params.featureAngle,
      chordTolerance: params.chordTolerance * diagonal,
      boundary: libraryBoundary(params.boundary),
      patches: true, // the flattened-domain view draws every patch in its plane
    };
  }

  async remesh(mesh: Mesh3, params: Params, diagonal: number, onProgress: (p: Progress) => void, signal: AbortSignal): Promise<RemeshOutput> {
    if (!this.canRemesh) throw new ConformeshError('InternalError', 'api', 'remesh is not available in this build');
    const fn = (this.remesher as unknown as Loose).remesh as (m: MeshLike, o: unknown, c: unknown) => Promise<unknown>;
    const raw = (await fn.call(this.remesher, mesh, this.options(params, diagonal), { onProgress, signal })) as Loose;
    const m = (pick(raw, 'mesh', 'output') as Loose | undefined) ?? raw;
    const positions = f64(m.positions);
    const triangles = u32(m.triangles);
    if (!positions || !triangles) throw new ConformeshError('InternalError', 'api', 'remesh returned no mesh');
    if (!raw.report || typeof raw.report !== 'object') throw new ConformeshError('InternalError', 'api', 'remesh returned no report');
    const out: RemeshOutput = {
      mesh: { positions, triangles },
      report: raw.report as RemeshReport,
      patches: patchesOf(pick(raw, 'patches', 'flat')),
    };
    const uvs = f64(m.uvs);
    if (uvs) out.mesh.uvs = uvs;
    if (Array.isArray(m.attributes) && m.attributes.length) out.mesh.attributes = m.attributes as MeshAttribute[];
    const pot = u32(pick(raw, 'patchOfTriangle', 'trianglePatch', 'facePatch', 'patchIds'));
    if (pot) out.patchOfTriangle = pot;
    const ipf = u32(pick(raw, 'inputPatchOfFace', 'inputFacePatch', 'segmentation'));
    if (ipf) out.inputPatchOfFace = ipf;
    else if (out.patches.some((p) => p.layout?.inputFace)) out.inputPatchOfFace = patchOfInputFace(out.patches, mesh.triangles.length / 3);
    const fe = u32(pick(raw, 'featureEdges', 'inputFeatureEdges'));
    if (fe) out.inputFeatureEdges = fe;
    return out;
  }

  async flatten(mesh: Mesh3, params: Params, diagonal: number, signal: AbortSignal): Promise<FlattenOutput> {
    if (!this.canFlatten) throw new ConformeshError('InternalError', 'api', 'flatten is not available in this build');
    const fn = (this.remesher as unknown as Loose).flatten as (m: MeshLike, o: unknown, c: unknown) => Promise<unknown>;
    const raw = (await fn.call(this.remesher, mesh, { boundary: libraryBoundary(params.boundary) }, { signal })) as Loose;
    // one patch (flatten works on a disk): uv and u per input vertex, over the input triangles
    // (raw.layout is the intrinsic triangulation in 3D coordinates, without u: not this)
    const list = (pick(raw, 'patches') as unknown[] | undefined) ?? [{ uv: raw.uv, factor: raw.u, triangles: mesh.triangles }];
    const out: FlattenOutput = { patches: patchesOf(list) };
    const ipf = u32(pick(raw, 'patchOfFace', 'inputPatchOfFace', 'facePatch'));
    if (ipf) out.inputPatchOfFace = ipf;
    return out;
  }
}
