// The synchronous API over one module instance. Each function checks its arguments (a wrong
// type is an InvalidArgument ConformeshError, never a crash inside the module), copies them into
// the shapes the glue expects, calls the glue through callRaw, and returns plain JS values.
import { progressBridge, type ProgressOptions } from './progress.js';
import { callRaw, requireExport, type RawModule } from './raw.js';
import { REMESH_OPTION_KEYS, type RemeshSchema } from './schema.js';
import type { StageName } from './stages.js';
import { ConformeshError, invalidArgument, type ErrorCode } from './status.js';
import type {
  FlattenOptions,
  FlattenResult,
  Pslg,
  PslgLike,
  Refine2dOptions,
  Refine2dResult,
  RemeshOptions,
  RemeshResult,
  Mesh,
  MeshAttribute,
  MeshBytes,
  MeshFormat,
  MeshInfo,
  MeshLike,
  ReadMeshOptions,
  ReadMeshResult,
  StatusRow,
  ValidateOptions,
  ValidateResult,
  WriteMeshOptions,
} from './types.js';

/** The API bound to one module instance; every method is synchronous. Obtain it with `init()`. */
export interface Conformesh {
  /** Library version ("0.1.0"). */
  readonly version: string;
  /** Threads a call runs on: above 1 in the threaded build (InitOptions.threads), else 1. */
  readonly threads: number;
  /** Read a mesh file's bytes. `format` or options: see ReadMeshOptions. */
  readMesh(bytes: MeshBytes, format?: MeshFormat | 'auto' | ReadMeshOptions): ReadMeshResult;
  /** Write a mesh to file bytes in `format`. */
  writeMesh(mesh: MeshLike, format: MeshFormat, options?: WriteMeshOptions): Uint8Array;
  /** Topology report (counts; does not fail on non-manifold input). */
  meshInfo(mesh: MeshLike, options?: Pick<ValidateOptions, 'maxVertices' | 'maxTriangles'>): MeshInfo;
  /** Validate and repair: a consistently oriented manifold mesh, or a ConformeshError saying why not. */
  validateMesh(mesh: MeshLike, options?: ValidateOptions): ValidateResult;
  /**
   * Quality triangulation of a planar straight-line graph (constrained Delaunay refinement):
   * every triangle that is not exempt gets min angle ≥ options.minAngle. `call` gives progress
   * and cancel (an aborted signal fails with 'Cancelled'). Failures: InvalidPslg, IndexOutOfRange,
   * NonFiniteCoordinate, InvalidArgument, Cancelled; reaching maxInsertions throws IterationLimit with
   * the valid mesh made so far as `error.result`.
   */
  refine2d(pslg: PslgLike, options?: Refine2dOptions, call?: ProgressOptions): Refine2dResult;
  /** Parse a Triangle .poly file into a PSLG (ParseError with the line number). */
  readPoly(bytes: MeshBytes): Pslg;
  /**
   * Conformal flattening of a disk-like patch (or a disk with holes) by discrete Ricci flow with
   * intrinsic Delaunay flips: uv per vertex, the conformal factor u, the intrinsic layout, the report.
   */
  flatten(mesh: MeshLike, options?: FlattenOptions, call?: ProgressOptions): FlattenResult;
  /** Remesh a surface (flatten per patch, planar refinement, lift): the new mesh and its quality report. */
  remesh(mesh: MeshLike, options?: RemeshOptions, call?: ProgressOptions): RemeshResult;
  /** The C++ status table. */
  statusTable(): StatusRow[];
  /** The C++ tables of remesh's options (name, kind, default, range, CLI flag, help) and report fields. */
  remeshSchema(): RemeshSchema;
  /** Bytes allocated in the module's heap, and the WASM memory size (for leak checks). */
  heapStats(): { used: number; heapSize: number };
}

const EMPTY_F64 = new Float64Array(0);

function isArrayLike(x: unknown): x is ArrayLike<number> {
  if (ArrayBuffer.isView(x)) return !(x instanceof DataView);
  return Array.isArray(x);
}

/** Bytes of a file argument as a Uint8Array (views on the caller's memory, no copy). */
export function toBytes(bytes: MeshBytes, stage: StageName = 'read'): Uint8Array {
  if (bytes instanceof Uint8Array) return bytes;
  if (typeof bytes === 'string') return new TextEncoder().encode(bytes);
  if (bytes instanceof ArrayBuffer) return new Uint8Array(bytes);
  if (ArrayBuffer.isView(bytes)) return new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  throw invalidArgument('mesh bytes must be a Uint8Array, an ArrayBuffer, a typed array or a string', stage);
}

function toFloat64(name: string, x: unknown, stage: StageName): Float64Array {
  if (x instanceof Float64Array) return x;
  if (!isArrayLike(x)) throw invalidArgument(`${name} must be a Float64Array or an array of numbers`, stage);
  return Float64Array.from(x, (v) => (typeof v === 'number' ? v : Number.NaN));
}

function toIndices(x: unknown, stage: StageName, name = 'triangles'): Uint32Array {
  if (x instanceof Uint32Array) return x;
  if (!isArrayLike(x)) throw invalidArgument(`${name} must be a Uint32Array or an array of vertex indices`, stage);
  const out = new Uint32Array(x.length);
  for (let i = 0; i < x.length; ++i) {
    const v = x[i];
    if (typeof v !== 'number' || !Number.isInteger(v)) {
      throw invalidArgument(`${name}[${i}] = ${String(v)} is not an integer vertex index`, stage);
    }
    if (v < 0 || v > 0xffffffff) {
      throw new ConformeshError('IndexOutOfRange', stage, `${name}[${i}] = ${v} is not a valid vertex index`);
    }
    out[i] = v;
  }
  return out;
}

/** The mesh's arrays in the element types the glue expects (copied only when needed). */
export function toMesh(mesh: unknown, stage: StageName = 'api'): Mesh {
  if (typeof mesh !== 'object' || mesh === null) {
    throw invalidArgument('mesh must be an object { positions, triangles, uvs? }', stage);
  }
  const m = mesh as Partial<MeshLike>;
  const out: Mesh = {
    positions: toFloat64('positions', m.positions, stage),
    triangles: toIndices(m.triangles, stage),
  };
  if (m.uvs !== undefined && m.uvs !== null) out.uvs = toFloat64('uvs', m.uvs, stage);
  if (m.attributes !== undefined && m.attributes !== null) out.attributes = toAttributes(m.attributes, stage);
  return out;
}

const NO_ATTRIBUTES: MeshAttribute[] = [];

/** A mesh's attributes in the shape the glue reads (plain objects; sizes are checked in C++). */
function toAttributes(x: unknown, stage: StageName): MeshAttribute[] {
  if (!Array.isArray(x)) throw invalidArgument('attributes must be an array of { name, itemSize, perCorner, values }', stage);
  return x.map((a: unknown, i) => {
    const o = a as Partial<MeshAttribute> | null;
    if (typeof o !== 'object' || o === null || typeof o.name !== 'string' || o.name === '') {
      throw invalidArgument(`attributes[${i}] needs a name`, stage);
    }
    if (typeof o.itemSize !== 'number' || !Number.isInteger(o.itemSize) || o.itemSize < 1 || o.itemSize > 0xffff) {
      throw invalidArgument(`attributes[${i}].itemSize must be an integer >= 1`, stage);
    }
    return {
      name: o.name,
      itemSize: o.itemSize,
      perCorner: o.perCorner === true,
      values: toFloat64(`attributes[${i}].values`, o.values, stage),
    };
  });
}

const EMPTY_U32 = new Uint32Array(0);
const EMPTY_I32 = new Int32Array(0);

function toInt32(name: string, x: unknown, stage: StageName): Int32Array {
  if (x instanceof Int32Array) return x;
  if (!isArrayLike(x)) throw invalidArgument(`${name} must be an Int32Array or an array of integers`, stage);
  const out = new Int32Array(x.length);
  for (let i = 0; i < x.length; ++i) {
    const v = x[i];
    if (typeof v !== 'number' || !Number.isInteger(v) || v < -0x80000000 || v > 0x7fffffff) {
      throw invalidArgument(`${name}[${i}] = ${String(v)} is not a 32-bit integer`, stage);
    }
    out[i] = v;
  }
  return out;
}

/** The PSLG's arrays in the element types the glue expects (copied only when needed). */
export function toPslg(pslg: unknown, stage: StageName = 'refine'): Pslg {
  if (typeof pslg !== 'object' || pslg === null) {
    throw invalidArgument('pslg must be an object { points, segments?, holes?, segmentMarkers? }', stage);
  }
  const p = pslg as Partial<PslgLike>;
  const out: Pslg = {
    points: toFloat64('points', p.points, stage),
    segments: p.segments == null ? EMPTY_U32 : toIndices(p.segments, stage, 'segments'),
    holes: p.holes == null ? EMPTY_F64 : toFloat64('holes', p.holes, stage),
  };
  if (p.segmentMarkers != null) out.segmentMarkers = toInt32('segmentMarkers', p.segmentMarkers, stage);
  return out;
}

const refineKeys: (keyof Refine2dOptions)[] = [
  'minAngle',
  'maxArea',
  'maxEdge',
  'maxInsertions',
  'convexHull',
  'holesByOrientation',
  'offcenters',
  'diametralLens',
];

const flattenKeys: (keyof FlattenOptions)[] = [
  'boundary',
  'cornerAngle',
  'flips',
  'tolerance',
  'maxIterations',
  'balanceMobius',
  'requireValidLayout',
];

const validateKeys: (keyof ValidateOptions)[] = [
  'maxVertices',
  'maxTriangles',
  'dropZeroAreaFaces',
  'dropDuplicateFaces',
  'fixOrientation',
  'splitNonManifoldVertices',
];

/**
 * A plain copy of the known option keys (the glue reads fields of the object it gets; getters or
 * proxies must not run inside a WASM call). Values are type-checked in C++ (InvalidArgument).
 */
export function pickOptions<T extends object>(options: T | undefined, keys: (keyof T)[], stage: StageName): Partial<T> {
  if (options === undefined || options === null) return {};
  if (typeof options !== 'object') throw invalidArgument('options must be an object', stage);
  const out: Partial<T> = {};
  for (const k of keys) {
    const v = options[k];
    if (v !== undefined) out[k] = typeof v === 'object' || typeof v === 'function' ? (String(v) as never) : v;
  }
  return out;
}

function readOptions(format: unknown): ReadMeshOptions {
  if (format === undefined || format === null) return {};
  if (typeof format === 'string') return { format: format as MeshFormat };
  if (typeof format === 'object') return format as ReadMeshOptions;
  throw invalidArgument('readMesh: the second argument must be a format name or an options object', 'read');
}

/** Bind the API to a raw module instance. */
export function bindApi(raw: RawModule): Conformesh {
  const api: Conformesh = {
    version: raw.version(),
    threads: raw.threads ?? 1,

    readMesh(bytes, format) {
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

    writeMesh(mesh, format, options = {}) {
      const m = toMesh(mesh, 'write');
      if (typeof format !== 'string') throw invalidArgument('writeMesh: format must be a format name', 'write');
      const fn = requireExport(raw, 'writeMesh');
      return callRaw(raw, 'writeMesh', 'write', () =>
        fn(
          m.positions,
          m.triangles,
          m.uvs ?? EMPTY_F64,
          m.attributes ?? NO_ATTRIBUTES,
          format,
          options.writeUvs !== false,
          options.writeAttributes !== false,
        ),
      );
    },

    meshInfo(mesh, options) {
      const m = toMesh(mesh, 'validate');
      const o = pickOptions(options, ['maxVertices', 'maxTriangles'], 'validate');
      const fn = requireExport(raw, 'meshInfo');
      return callRaw(raw, 'meshInfo', 'validate', () => fn(m.positions, m.triangles, o));
    },

    validateMesh(mesh, options) {
      const m = toMesh(mesh, 'validate');
      const o = pickOptions(options, validateKeys, 'validate');
      const fn = requireExport(raw, 'validateMesh');
      return callRaw(raw, 'validateMesh', 'validate', () => fn(m.positions, m.triangles, m.uvs ?? EMPTY_F64, o));
    },

    refine2d(pslg, options, call) {
      const p = toPslg(pslg);
      const o = pickOptions(options, refineKeys, 'refine');
      const fn = requireExport(raw, 'refine2d');
      const bridge = progressBridge(call);
      try {
        const r = callRaw(raw, 'refine2d', 'refine', () =>
          fn(p.points, p.segments ?? EMPTY_U32, p.segmentMarkers ?? EMPTY_I32, p.holes ?? EMPTY_F64, o, bridge.fn),
        );
        // every status but Ok throws; the partial mesh goes with the error
        if (r.status !== 'Ok') throw new ConformeshError(r.status as ErrorCode, 'refine', r.message, r);
        return r;
      } finally {
        bridge.rethrow();
      }
    },

    readPoly(bytes) {
      const data = toBytes(bytes);
      const fn = requireExport(raw, 'readPoly');
      return callRaw(raw, 'readPoly', 'read', () => fn(data));
    },

    flatten(mesh, options, call) {
      const m = toMesh(mesh, 'flatten');
      const o = pickOptions(options, flattenKeys, 'flatten');
      const fn = requireExport(raw, 'flatten');
      const bridge = progressBridge(call);
      try {
        return callRaw(raw, 'flatten', 'flatten', () => fn(m.positions, m.triangles, o, bridge.fn));
      } finally {
        bridge.rethrow();
      }
    },

    remesh(mesh, options, call) {
      const m = toMesh(mesh, 'api');
      const o = pickOptions(options, REMESH_OPTION_KEYS, 'api');
      const sizing = options?.vertexSizing == null ? EMPTY_F64 : toFloat64('vertexSizing', options.vertexSizing, 'api');
      const features =
        options?.featureEdges == null ? EMPTY_U32 : toIndices(options.featureEdges, 'api', 'featureEdges');
      const fn = requireExport(raw, 'remesh');
      const bridge = progressBridge(call);
      try {
        return callRaw(raw, 'remesh', 'api', () =>
          fn(m.positions, m.triangles, m.uvs ?? EMPTY_F64, m.attributes ?? NO_ATTRIBUTES, sizing, features, o, bridge.fn),
        );
      } finally {
        bridge.rethrow();
      }
    },

    statusTable() {
      return raw.statusTable();
    },

    remeshSchema() {
      return raw.remeshSchema();
    },

    heapStats() {
      return raw.heapStats();
    },
  };
  return Object.freeze(api);
}
