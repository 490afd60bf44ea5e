// Argument conversion shared by the direct API (methods.ts) and the worker client (remesher.ts):
// a wrong type is an InvalidArgument ConformeshError, never a crash inside the module; arrays
// come out in the element types the glue expects, copied only when needed.
import type { StageName } from './stages.js';
import { ConformeshError, invalidArgument } from './status.js';
import type {
  FlattenOptions,
  Mesh,
  MeshAttribute,
  MeshBytes,
  MeshFormat,
  MeshLike,
  Pslg,
  PslgLike,
  ReadMeshOptions,
  Refine2dOptions,
  ValidateOptions,
} from './types.js';

export const EMPTY_F64 = new Float64Array(0);

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

export function toFloat64(name: string, x: unknown, stage: StageName): Float64Array {
  if (x instanceof Float64Array) return x;
  if (!isArrayLike(x)) throw invalidArgument(`${name} must be a Float64Array or an array of numbers`, stage);
  return Float64Array.from(x, (v) => (typeof v === 'number' ? v : Number.NaN));
}

export function toIndices(x: unknown, stage: StageName, name = 'triangles'): Uint32Array {
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

export const NO_ATTRIBUTES: MeshAttribute[] = [];

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

export const EMPTY_U32 = new Uint32Array(0);
export const EMPTY_I32 = new Int32Array(0);

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

export const refineKeys: (keyof Refine2dOptions)[] = [
  'minAngle',
  'maxArea',
  'maxEdge',
  'maxInsertions',
  'convexHull',
  'holesByOrientation',
  'offcenters',
  'diametralLens',
];

export const flattenKeys: (keyof FlattenOptions)[] = [
  'boundary',
  'cornerAngle',
  'flips',
  'tolerance',
  'maxIterations',
  'balanceMobius',
  'requireValidLayout',
];

export const validateKeys: (keyof ValidateOptions)[] = [
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

export function readOptions(format: unknown): ReadMeshOptions {
  if (format === undefined || format === null) return {};
  if (typeof format === 'string') return { format: format as MeshFormat };
  if (typeof format === 'object') return format as ReadMeshOptions;
  throw invalidArgument('readMesh: the second argument must be a format name or an options object', 'read');
}

/** Options as a structured-clone-safe plain object (own enumerable fields only), for a worker. */
export function plainOptions<T extends object>(options: T | undefined): T | undefined {
  if (options === undefined || options === null) return undefined;
  if (typeof options !== 'object') throw invalidArgument('options must be an object');
  return { ...options };
}
