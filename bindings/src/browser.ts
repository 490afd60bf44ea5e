// conformesh — public API of the npm package; this file is its browser entry (package.json
// "exports" default condition), and index.ts, the Node entry, re-exports it. Nothing here names a
// Node builtin (platform.ts).
//
//   import { readMesh, writeMesh, meshInfo, validateMesh } from 'conformesh';  // async, lazy module load
//   const cm = await init(); cm.readMesh(bytes);                       // or: synchronous after init()
//   const remesher = createRemesher({ workers: 2 });                   // the same API in Web Workers
//
// Results are plain objects of typed arrays copied out of the WebAssembly heap: nothing to free.
// Failures throw ConformeshError { code, value, stage, message }.
import { bindApi, type Conformesh } from './api.js';
import { loadRaw, type InitOptions } from './loader.js';
import type { ProgressOptions } from './progress.js';
import type {
  FlattenOptions,
  FlattenResult,
  Pslg,
  PslgLike,
  Refine2dOptions,
  Refine2dResult,
  RemeshOptions,
  RemeshResult,
  MeshBytes,
  MeshFormat,
  MeshInfo,
  MeshLike,
  ReadMeshOptions,
  ReadMeshResult,
  ValidateOptions,
  ValidateResult,
  WriteMeshOptions,
} from './types.js';

export type { Conformesh } from './api.js';
export type { InitOptions } from './loader.js';
export type { ProgressOptions } from './progress.js';
export * from './types.js';
export { ConformeshError, StatusCode, type ConformeshErrorData, type ErrorCode, type StatusCodeName } from './status.js';
export {
  REMESH_STAGES,
  STAGES,
  Stage,
  stageInterval,
  type RemeshStageRow,
  type StageName,
  type StageRow,
  type StageSeconds,
} from './stages.js';
export { EXEMPT_CORNER_KEYS, REMESH_OPTION_KEYS, REMESH_REPORT_KEYS, type OptionKind, type OptionRow, type RemeshSchema } from './schema.js';
export { createRemesher, type Remesher, type RemesherOptions, type CallOptions, type ProgressEvent } from './remesher.js';

let api: Promise<Conformesh> | undefined;

/**
 * Load the WebAssembly module (once; later calls return the same instance) and return the
 * synchronous API. Options apply to the first call only. Rejects with ConformeshError IoError
 * when the .wasm cannot be loaded.
 */
export function init(options?: InitOptions): Promise<Conformesh> {
  if (!api) {
    api = loadRaw(options).then(bindApi, (e: unknown) => {
      api = undefined;
      throw e;
    });
  }
  return api;
}

/** Read a mesh file's bytes (OBJ, OFF, STL ascii/binary, PLY ascii/binary). */
export async function readMesh(bytes: MeshBytes, format?: MeshFormat | 'auto' | ReadMeshOptions): Promise<ReadMeshResult> {
  return (await init()).readMesh(bytes, format);
}

/** Write a mesh to file bytes. */
export async function writeMesh(mesh: MeshLike, format: MeshFormat, options?: WriteMeshOptions): Promise<Uint8Array> {
  return (await init()).writeMesh(mesh, format, options);
}

/** Topology report: vertices, faces, components, boundaryLoops, euler, genus, ... (never fails on non-manifold input). */
export async function meshInfo(mesh: MeshLike, options?: Pick<ValidateOptions, 'maxVertices' | 'maxTriangles'>): Promise<MeshInfo> {
  return (await init()).meshInfo(mesh, options);
}

/** Validate and repair a mesh (see ValidateOptions): the repaired mesh and what was done, or a ConformeshError. */
export async function validateMesh(mesh: MeshLike, options?: ValidateOptions): Promise<ValidateResult> {
  return (await init()).validateMesh(mesh, options);
}

/**
 * Quality triangulation of a planar straight-line graph (constrained Delaunay refinement; see
 * Refine2dOptions). `call`: { onProgress, signal } (runs on this thread; use createRemesher for workers).
 */
export async function refine2d(pslg: PslgLike, options?: Refine2dOptions, call?: ProgressOptions): Promise<Refine2dResult> {
  return (await init()).refine2d(pslg, options, call);
}

/** Parse a Triangle .poly file into a PSLG. */
export async function readPoly(bytes: MeshBytes): Promise<Pslg> {
  return (await init()).readPoly(bytes);
}

/** Conformal flattening of a disk-like patch: uv per vertex, conformal factor u, intrinsic layout, report. */
export async function flatten(mesh: MeshLike, options?: FlattenOptions, call?: ProgressOptions): Promise<FlattenResult> {
  return (await init()).flatten(mesh, options, call);
}

/** Remesh a surface: the new mesh and its quality report. */
export async function remesh(mesh: MeshLike, options?: RemeshOptions, call?: ProgressOptions): Promise<RemeshResult> {
  return (await init()).remesh(mesh, options, call);
}
