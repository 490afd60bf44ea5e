// Public data types of the package.
import type { StatusCodeName } from './status.js';

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

/** A non-fatal finding: the status it stands for (or 'Ok' for a note), how many elements, a message. */
export interface MeshWarning {
  code: StatusCodeName;
  count: number;
  message: string;
}

/**
 * Topology report (what `conformesh info --json` prints). Never fails on non-manifold or badly
 * oriented input: it counts what it finds. Degenerate triangles are counted and left out of the
 * rest; `genus` = (2·components − euler − boundaryLoops) / 2, fractional when not a manifold.
 */
export interface MeshInfo {
  vertices: number;
  faces: number;
  edges: number;
  components: number;
  boundaryLoops: number;
  euler: number;
  genus: number;
  nonManifoldEdges: number;
  nonManifoldVertices: number;
  degenerateFaces: number;
  duplicateFaces: number;
  inconsistentFaces: number;
  warnings: MeshWarning[];
}

/** How validateMesh repairs (and the size limits meshInfo also applies). */
export interface ValidateOptions {
  /** More vertices fail with TooLarge; default 16 M (16·2^20). */
  maxVertices?: number;
  /** More triangles fail with TooLarge; default 16 M. */
  maxTriangles?: number;
  /** Drop exactly-zero-area triangles (default true); repeated-vertex triangles are always dropped. */
  dropZeroAreaFaces?: boolean;
  /** Drop duplicate triangles instead of failing with NonManifoldEdge (default false). */
  dropDuplicateFaces?: boolean;
  /** Make the orientation consistent (default true); false: InconsistentOrientation is an error. */
  fixOrientation?: boolean;
  /** Give each extra fan of a bow-tie vertex its own vertex instead of failing (default false). */
  splitNonManifoldVertices?: boolean;
}

/** What validateMesh repaired. */
export interface ValidationReport {
  inputVertices: number;
  inputTriangles: number;
  degenerateFaces: number;
  zeroAreaFaces: number;
  duplicateFaces: number;
  flippedFaces: number;
  splitVertices: number;
  removedVertices: number;
  warnings: MeshWarning[];
}

export interface ValidateResult {
  /** The repaired mesh (a consistently oriented manifold). */
  mesh: Mesh;
  report: ValidationReport;
  /** For each output vertex, its input vertex. */
  vertexToInput: Uint32Array;
  /** For each output triangle, its input triangle. */
  faceToInput: Uint32Array;
}

/** One row of the status table (the C++ table, exported by the module). */
export interface StatusRow {
  code: number;
  name: string;
  fatal: boolean;
  meaning: string;
}
