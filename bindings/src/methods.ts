// The package's methods, one row each: argument and result types (from `run`'s signature), the
// stage that argument errors and the last progress report name, whether the call takes progress
// and cancel, and how each argument crosses to a worker. The direct API (api.ts), the lazy async
// functions (browser.ts), the worker client (remesher.ts) and the worker's dispatch (worker.ts)
// are derived from this table: a new method is one row here plus its glue (docs/BINDINGS.md).
// Results cross from a worker with every typed array's buffer transferred (protocol.ts).
import {
  EMPTY_F64,
  EMPTY_I32,
  EMPTY_U32,
  NO_ATTRIBUTES,
  flattenKeys,
  pickOptions,
  plainOptions,
  readOptions,
  refineKeys,
  toBytes,
  toFloat64,
  toIndices,
  toMesh,
  toPslg,
  validateKeys,
} from './convert.js';
import { progressBridge, type ProgressOptions } from './progress.js';
import { callRaw, requireExport, type RawModule } from './raw.js';
import { REMESH_OPTION_KEYS } from './schema.js';
import type { StageName } from './stages.js';
import { invalidArgument } from './status.js';
import type {
  FlattenOptions,
  FlattenResult,
  MeshBytes,
  MeshFormat,
  MeshInfo,
  MeshLike,
  Pslg,
  PslgLike,
  ReadMeshOptions,
  ReadMeshResult,
  Refine2dOptions,
  Refine2dResult,
  RemeshOptions,
  RemeshResult,
  ValidateOptions,
  ValidateResult,
  WriteMeshOptions,
} from './types.js';

/**
 * How an argument crosses to a worker (checked and copied on the caller's side, so a bad argument
 * fails before anything is posted): file bytes, a mesh, a PSLG, an options object copied to a
 * plain one, or a value sent as it is.
 */
export type ArgKind = 'bytes' | 'mesh' | 'pslg' | 'options' | 'value';

export interface MethodRow<A extends unknown[], R, P extends boolean> {
  /** The stage of argument errors and of the final progress report (when the call made none). */
  stage: StageName;
  /** Takes { onProgress, signal } after its arguments (direct) and reports progress (worker). */
  progress: P;
  /** One kind per argument, in order. */
  send: NoInfer<{ [I in keyof A]-?: ArgKind }>;
  /** The implementation over the raw module; `call` is undefined for a method without progress. */
  run(raw: RawModule, call: ProgressOptions | undefined, ...args: A): R;
}

function row<A extends unknown[], R, P extends boolean>(r: MethodRow<A, R, P>): MethodRow<A, R, P> {
  return r;
}

/** Run a glue call with a progress bridge; what the user's listener threw is rethrown after it. */
function withProgress<T>(call: ProgressOptions | undefined, body: (fn: ReturnType<typeof progressBridge>['fn']) => T): T {
  const bridge = progressBridge(call);
  try {
    return body(bridge.fn);
  } finally {
    bridge.rethrow();
  }
}

export const METHODS = {
  /** Read a mesh file's bytes (OBJ, OFF, STL ascii/binary, PLY ascii/binary). `format` or options: see ReadMeshOptions. */
  readMesh: row({
    stage: 'read',
    progress: false,
    send: ['bytes', 'value'],
    run(raw: RawModule, _call: ProgressOptions | undefined, bytes: MeshBytes, format?: MeshFormat | 'auto' | ReadMeshOptions): ReadMeshResult {
      const data = toBytes(bytes);
      const o = readOptions(format);
      const weld = o.weldTolerance ?? 0;
      if (typeof weld !== 'number') throw invalidArgument('weldTolerance must be a number', 'read');
      const fn = requireExport(raw, 'readMesh');
      const r = callRaw(raw, 'readMesh', 'read', () =>
        fn(data, String(o.format ?? 'auto'), String(o.fileName ?? ''), weld, o.readUvs !== false, o.readAttributes !== false),
      );
      const out: ReadMeshResult = {
        positions: r.positions,
        triangles: r.triangles,
        format: r.format as MeshFormat,
        warnings: r.warnings,
      };
      if (r.uvs) out.uvs = r.uvs;
      if (r.attributes) out.attributes = r.attributes;
      return out;
    },
  }),

  /** Write a mesh to file bytes in `format`. */
  writeMesh: row({
    stage: 'write',
    progress: false,
    send: ['mesh', 'value', 'value'],
    run(raw: RawModule, _call: ProgressOptions | undefined, mesh: MeshLike, format: MeshFormat, options?: WriteMeshOptions): Uint8Array {
      const m = toMesh(mesh, 'write');
      if (typeof format !== 'string') throw invalidArgument('writeMesh: format must be a format name', 'write');
      const o = options ?? {};
      const fn = requireExport(raw, 'writeMesh');
      return callRaw(raw, 'writeMesh', 'write', () =>
        fn(m.positions, m.triangles, m.uvs ?? EMPTY_F64, m.attributes ?? NO_ATTRIBUTES, format, o.writeUvs !== false, o.writeAttributes !== false),
      );
    },
  }),

  /** Topology report: vertices, faces, components, boundaryLoops, euler, genus, ... (never fails on non-manifold input). */
  meshInfo: row({
    stage: 'validate',
    progress: false,
    send: ['mesh', 'value'],
    run(raw: RawModule, _call: ProgressOptions | undefined, mesh: MeshLike, options?: Pick<ValidateOptions, 'maxVertices' | 'maxTriangles'>): MeshInfo {
      const m = toMesh(mesh, 'validate');
      const o = pickOptions(options, ['maxVertices', 'maxTriangles'], 'validate');
      const fn = requireExport(raw, 'meshInfo');
      return callRaw(raw, 'meshInfo', 'validate', () => fn(m.positions, m.triangles, o));
    },
  }),

  /** Validate and repair: a consistently oriented manifold mesh and what was done, or a ConformeshError saying why not. */
  validateMesh: row({
    stage: 'validate',
    progress: false,
    send: ['mesh', 'value'],
    run(raw: RawModule, _call: ProgressOptions | undefined, mesh: MeshLike, options?: ValidateOptions): ValidateResult {
      const m = toMesh(mesh, 'validate');
      const o = pickOptions(options, validateKeys, 'validate');
      const fn = requireExport(raw, 'validateMesh');
      return callRaw(raw, 'validateMesh', 'validate', () => fn(m.positions, m.triangles, m.uvs ?? EMPTY_F64, o));
    },
  }),

  /**
   * Quality triangulation of a planar straight-line graph (constrained Delaunay refinement):
   * every triangle that is not exempt gets min angle ≥ options.minAngle. `call` gives progress
   * and cancel (an aborted signal fails with 'Cancelled'). Failures: InvalidPslg, IndexOutOfRange,
   * NonFiniteCoordinate, InvalidArgument, Cancelled; reaching maxInsertions throws IterationLimit with
   * the valid mesh made so far as `error.result`.
   */
  refine2d: row({
    stage: 'refine',
    progress: true,
    send: ['pslg', 'options'],
    run(raw: RawModule, call: ProgressOptions | undefined, pslg: PslgLike, options?: Refine2dOptions): Refine2dResult {
      const p = toPslg(pslg);
      const o = pickOptions(options, refineKeys, 'refine');
      const fn = requireExport(raw, 'refine2d');
      return withProgress(call, (progress) =>
        callRaw(raw, 'refine2d', 'refine', () =>
          fn(p.points, p.segments ?? EMPTY_U32, p.segmentMarkers ?? EMPTY_I32, p.holes ?? EMPTY_F64, o, progress),
        ),
      );
    },
  }),

  /** Parse a Triangle .poly file into a PSLG (ParseError with the line number). */
  readPoly: row({
    stage: 'read',
    progress: false,
    send: ['bytes'],
    run(raw: RawModule, _call: ProgressOptions | undefined, bytes: MeshBytes): Pslg {
      const data = toBytes(bytes);
      const fn = requireExport(raw, 'readPoly');
      return callRaw(raw, 'readPoly', 'read', () => fn(data));
    },
  }),

  /**
   * Conformal flattening of a disk-like patch (or a disk with holes) by discrete Ricci flow with
   * intrinsic Delaunay flips: uv per vertex, the conformal factor u, the intrinsic layout, the report.
   */
  flatten: row({
    stage: 'flatten',
    progress: true,
    send: ['mesh', 'options'],
    run(raw: RawModule, call: ProgressOptions | undefined, mesh: MeshLike, options?: FlattenOptions): FlattenResult {
      const m = toMesh(mesh, 'flatten');
      const o = pickOptions(options, flattenKeys, 'flatten');
      const fn = requireExport(raw, 'flatten');
      return withProgress(call, (progress) => callRaw(raw, 'flatten', 'flatten', () => fn(m.positions, m.triangles, o, progress)));
    },
  }),

  /** Remesh a surface (flatten per patch, planar refinement, lift): the new mesh and its quality report. */
  remesh: row({
    stage: 'api',
    progress: true,
    send: ['mesh', 'options'],
    run(raw: RawModule, call: ProgressOptions | undefined, mesh: MeshLike, options?: RemeshOptions): RemeshResult {
      const m = toMesh(mesh, 'api');
      const o = pickOptions(options, REMESH_OPTION_KEYS, 'api');
      const sizing = options?.vertexSizing == null ? EMPTY_F64 : toFloat64('vertexSizing', options.vertexSizing, 'api');
      const features = options?.featureEdges == null ? EMPTY_U32 : toIndices(options.featureEdges, 'api', 'featureEdges');
      const fn = requireExport(raw, 'remesh');
      return withProgress(call, (progress) =>
        callRaw(raw, 'remesh', 'api', () =>
          fn(m.positions, m.triangles, m.uvs ?? EMPTY_F64, m.attributes ?? NO_ATTRIBUTES, sizing, features, o, progress),
        ),
      );
    },
  }),
};

export type Methods = typeof METHODS;
export type MethodName = keyof Methods;
export const METHOD_NAMES = Object.keys(METHODS) as MethodName[];

/** A method's arguments (without the per-call options) and its result. */
export type ArgsOf<K extends MethodName> = Methods[K] extends MethodRow<infer A, unknown, boolean> ? A : never;
export type ResultOf<K extends MethodName> = ReturnType<Methods[K]['run']>;

/** The synchronous signatures: a method with progress takes { onProgress, signal } last. */
export type DirectMethods = {
  [K in keyof Methods]: Methods[K]['progress'] extends true
    ? (...args: [...ArgsOf<K>, call?: ProgressOptions]) => ResultOf<K>
    : (...args: ArgsOf<K>) => ResultOf<K>;
};

/** The lazy async signatures of the package's top-level functions (browser.ts). */
export type AsyncDirectMethods = {
  [K in keyof DirectMethods]: (...args: Parameters<DirectMethods[K]>) => Promise<ResultOf<K>>;
};

/** The worker client's signatures: every method takes the worker call's options last. */
export type WorkerMethods<Call> = {
  [K in keyof Methods]: (...args: [...ArgsOf<K>, call?: Call]) => Promise<ResultOf<K>>;
};

/** The table's methods bound to one module instance. */
export function bindMethods(raw: RawModule): DirectMethods {
  const out: Record<string, unknown> = {};
  for (const name of METHOD_NAMES) {
    const r = METHODS[name] as MethodRow<unknown[], unknown, boolean>;
    const arity = r.send.length;
    out[name] = (...args: unknown[]) =>
      r.run(raw, r.progress ? (args[arity] as ProgressOptions | undefined) : undefined, ...args.slice(0, arity));
  }
  return out as DirectMethods;
}

/** A method's arguments checked and copied for posting to a worker (the row's `send` kinds). */
export function sendArgs(name: MethodName, args: unknown[]): unknown[] {
  const r = METHODS[name] as MethodRow<unknown[], unknown, boolean>;
  return r.send.map((kind, i) => {
    const a = args[i];
    if (kind === 'bytes') return toBytes(a as MeshBytes, r.stage);
    if (kind === 'mesh') return toMesh(a, r.stage);
    if (kind === 'pslg') return toPslg(a, r.stage);
    if (kind === 'options') return plainOptions(a as object | undefined);
    return a;
  });
}
