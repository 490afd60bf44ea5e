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
import type { AsyncDirectMethods, MethodName } from './methods.js';

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

/** The table's method `name` as an async function that loads the module on first use. */
function lazy<K extends MethodName>(name: K): AsyncDirectMethods[K] {
  return (async (...args: unknown[]) => ((await init())[name] as (...a: unknown[]) => unknown)(...args)) as AsyncDirectMethods[K];
}

/** Read a mesh file's bytes (OBJ, OFF, STL ascii/binary, PLY ascii/binary). */
export const readMesh = lazy('readMesh');
/** Write a mesh to file bytes. */
export const writeMesh = lazy('writeMesh');
/** Topology report: vertices, faces, components, boundaryLoops, euler, genus, ... (never fails on non-manifold input). */
export const meshInfo = lazy('meshInfo');
/** Validate and repair a mesh (see ValidateOptions): the repaired mesh and what was done, or a ConformeshError. */
export const validateMesh = lazy('validateMesh');
/**
 * Quality triangulation of a planar straight-line graph (constrained Delaunay refinement; see
 * Refine2dOptions). `call`: { onProgress, signal } (runs on this thread; use createRemesher for workers).
 */
export const refine2d = lazy('refine2d');
/** Parse a Triangle .poly file into a PSLG. */
export const readPoly = lazy('readPoly');
/** Conformal flattening of a disk-like patch: uv per vertex, conformal factor u, intrinsic layout, report. */
export const flatten = lazy('flatten');
/** Remesh a surface: the new mesh and its quality report. */
export const remesh = lazy('remesh');
