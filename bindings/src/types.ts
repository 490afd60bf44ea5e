// Public data types of the package.

/**
 * A triangle mesh as flat arrays (GL style; maps one-to-one onto three.js BufferAttributes).
 *   positions  3·nV numbers, x y z per vertex
 *   triangles  3·nF vertex indices (0-based), counter-clockwise seen from outside
 *   uvs        optional, 2·nV numbers (per-vertex planar coordinates)
 */
export interface Mesh {
  positions: Float64Array;
  triangles: Uint32Array;
  uvs?: Float64Array;
}

/**
 * What the API accepts as a mesh: the arrays may also be other typed arrays or plain number
 * arrays (copied; indices must be integers >= 0).
 */
export interface MeshLike {
  positions: ArrayLike<number>;
  triangles: ArrayLike<number>;
  uvs?: ArrayLike<number> | undefined;
}

/** File formats: `stl` and `ply` are the binary (little-endian) variants. */
export type MeshFormat = 'obj' | 'off' | 'stl' | 'stl-ascii' | 'ply' | 'ply-ascii' | 'ply-be';

/** File contents: bytes, or text (encoded as UTF-8). */
export type MeshBytes = Uint8Array | ArrayBuffer | ArrayBufferView | string;

export interface ReadMeshOptions {
  /** Default 'auto': detected from the content, then from `fileName`'s extension. */
  format?: MeshFormat | 'auto';
  /** Only a hint for format detection and error messages. */
  fileName?: string;
  /** Also weld vertices closer than this (absolute units); default 0 (exact duplicates in STL only). */
  weldTolerance?: number;
  /** Keep OBJ `vt` as `uvs` when every used vertex has exactly one; default true. */
  readUvs?: boolean;
}

export interface ReadMeshResult extends Mesh {
  /** The format actually read. */
  format: MeshFormat;
  /** Non-fatal findings (welded vertices, skipped elements). */
  warnings: string[];
}

export interface WriteMeshOptions {
  /** OBJ: write `vt` when the mesh has uvs; default true. */
  writeUvs?: boolean;
}

/** Validation and topology report; the same keys as `conformesh info --json`. */
export interface MeshInfo {
  vertices: number;
  faces: number;
  components: number;
  boundaryLoops: number;
  euler: number;
  genus: number;
  nonManifoldEdges: number;
  degenerateFaces: number;
  warnings: string[];
}

/** One row of the status table (the C++ table, exported by the module). */
export interface StatusRow {
  code: number;
  name: string;
  fatal: boolean;
  meaning: string;
}
