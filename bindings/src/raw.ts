// The raw Emscripten module (dist/conformesh.mjs + .wasm) as the facade sees it, and the one
// place where its results become values or ConformeshErrors. Internal: not part of the public API.
import type { RemeshSchema } from './schema.js';
import { isStageName, type StageName } from './stages.js';
import { ConformeshError, isErrorCode } from './status.js';
import type { FlattenResult, MeshAttribute, MeshInfo, Pslg, Refine2dResult, RemeshResult, ValidateResult } from './types.js';

/**
 * What every fallible glue function returns (bindings/binding_util.h, `guarded`). A failure may
 * carry the result it was computed with (remesh with keepDefectiveOutput).
 */
export type RawResult<T> =
  | { ok: true; value: T }
  | { ok: false; code: number; name: string; stage: string; message: string; result?: T };

export interface RawMesh {
  positions: Float64Array;
  triangles: Uint32Array;
  uvs?: Float64Array;
  attributes?: MeshAttribute[];
}

export interface RawStatusRow {
  code: number;
  name: string;
  fatal: boolean;
  meaning: string;
}

/** The embind exports (bindings/*.cpp). Functions of areas not built yet are absent. */
export interface RawModule {
  version(): string;
  statusTable(): RawStatusRow[];
  /** conformesh/remesh_schema.h: the option rows and the report's field names. */
  remeshSchema(): RemeshSchema;
  /** core/stages.h: a row per stage, with its progress interval (lo, hi) in a remesh. */
  stageTable(): { stage: number; name: string; key: string; label: string; weight: number; timed: boolean; lo: number; hi: number }[];
  heapStats(): { used: number; heapSize: number };
  progressSelfTest(steps: number, progress: ((stage: number, fraction: number) => boolean) | undefined): RawResult<number>;
  readMesh?(
    bytes: Uint8Array,
    format: string,
    fileName: string,
    weldTolerance: number,
    readUvs: boolean,
    readAttributes: boolean,
  ): RawResult<RawMesh & { format: string; warnings: string[] }>;
  writeMesh?(
    positions: Float64Array,
    triangles: Uint32Array,
    uvs: Float64Array,
    attributes: MeshAttribute[],
    format: string,
    writeUvs: boolean,
    writeAttributes: boolean,
  ): RawResult<Uint8Array>;
  meshInfo?(positions: Float64Array, triangles: Uint32Array, options: object): RawResult<MeshInfo>;
  validateMesh?(positions: Float64Array, triangles: Uint32Array, uvs: Float64Array, options: object): RawResult<ValidateResult>;
  refine2d?(
    points: Float64Array,
    segments: Uint32Array,
    segmentMarkers: Int32Array,
    holes: Float64Array,
    options: object,
    progress: ((stage: number, fraction: number) => boolean) | undefined,
  ): RawResult<Refine2dResult>;
  readPoly?(bytes: Uint8Array): RawResult<Pslg>;
  flatten?(
    positions: Float64Array,
    triangles: Uint32Array,
    options: object,
    progress: ((stage: number, fraction: number) => boolean) | undefined,
  ): RawResult<FlattenResult>;
  remesh?(
    positions: Float64Array,
    triangles: Uint32Array,
    uvs: Float64Array,
    attributes: MeshAttribute[],
    vertexSizing: Float64Array,
    featureEdges: Uint32Array,
    options: object,
    progress: ((stage: number, fraction: number) => boolean) | undefined,
  ): RawResult<RemeshResult>;
  stackSave(): number;
  stackRestore(sp: number): void;
  HEAP8: Int8Array;
  /** Threads a call runs on (set by the loader; 1 for the single-threaded build). */
  threads?: number;
}

/** Options accepted by the Emscripten factory (the subset we use). */
export interface RawModuleOptions {
  wasmBinary?: ArrayBuffer | Uint8Array;
  instantiateWasm?: (
    imports: WebAssembly.Imports,
    receive: (instance: WebAssembly.Instance, module?: WebAssembly.Module) => void,
  ) => object;
  print?: (text: string) => void;
  printErr?: (text: string) => void;
  /** Threaded build: pthread workers started with the module (-sPTHREAD_POOL_SIZE=Module.pthreadPoolSize). */
  pthreadPoolSize?: number;
  /** Threaded build: the glue's URL, which each pthread worker imports. */
  mainScriptUrlOrBlob?: string;
  /** Where the glue's companion files are (the pthread worker script). */
  locateFile?: (path: string, prefix: string) => string;
}

export type RawFactory = (options?: RawModuleOptions) => Promise<RawModule>;

/**
 * Call a glue function and unwrap its result. The stack pointer is saved and restored around the
 * call, so even a JS exception thrown inside (an embind argument check, a bug) leaves the WASM
 * stack as it was (Emscripten 3.1.6 leaks stack on every throw through WASM frames otherwise).
 */
export function callRaw<T>(raw: RawModule, name: string, stage: StageName, fn: () => RawResult<T>): T {
  const sp = raw.stackSave();
  let result: RawResult<T>;
  try {
    result = fn();
  } catch (e) {
    raw.stackRestore(sp);
    if (e instanceof ConformeshError) throw e;
    const message = e instanceof Error ? e.message : String(e);
    throw new ConformeshError('InternalError', stage, `${name}: unexpected exception in the WebAssembly module: ${message}`);
  }
  if (result.ok) {
    // one error model: a value that carries a status other than Ok is thrown, the value attached
    const v = result.value as { status?: unknown; message?: unknown } | null;
    if (v === null || typeof v !== 'object' || typeof v.status !== 'string' || v.status === 'Ok') return result.value;
    throw new ConformeshError(isErrorCode(v.status) ? v.status : 'InternalError', stage, String(v.message ?? ''), v as Refine2dResult);
  }
  throw new ConformeshError(
    isErrorCode(result.name) ? result.name : 'InternalError',
    isStageName(result.stage) ? result.stage : stage,
    result.message,
    result.result as RemeshResult | undefined,
  );
}

/** The glue function `name`, or an InternalError if this build of the module lacks it. */
export function requireExport<K extends keyof RawModule>(raw: RawModule, name: K): NonNullable<RawModule[K]> {
  const f = raw[name];
  if (typeof f !== 'function') {
    throw new ConformeshError('InternalError', 'api', `this build of the WebAssembly module has no '${String(name)}'`);
  }
  return (f as (...args: never[]) => unknown).bind(raw) as NonNullable<RawModule[K]>;
}
