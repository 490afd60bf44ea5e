// Public data types of the package.
import type { StageSeconds } from './stages.js';
import type { StatusCodeName } from './status.js';

/**
 * Data attached to a mesh's vertices or triangle corners, as read from a file (OBJ vt / vn, PLY
 * colours, normals, any scalar vertex property) and carried through remesh.
 *   name       'uv' (itemSize 2, only per corner: per-vertex uvs are Mesh.uvs), 'normal' (3),
 *              'color' (3 or 4, in [0, 1]) or a PLY vertex property's own name (1)
 *   itemSize   values per item
 *   perCorner  false: one item per vertex (nV·itemSize values); true: one per triangle corner
 *              (corner c of triangle t is item 3·t + c; 3·nF·itemSize values): a vertex on a seam
 *              has one value per side. `conformesh/three` splits such vertices for three.js.
 */
export interface MeshAttribute {
  name: string;
  itemSize: number;
  perCorner: boolean;
  values: Float64Array;
}

/**
 * A triangle mesh as flat arrays (GL style; maps one-to-one onto three.js BufferAttributes).
 *   positions   3·nV numbers, x y z per vertex
 *   triangles   3·nF vertex indices (0-based), counter-clockwise seen from outside
 *   uvs         optional, 2·nV numbers (per-vertex planar coordinates)
 *   attributes  optional, other data per vertex or per corner (MeshAttribute)
 */
export interface Mesh {
  positions: Float64Array;
  triangles: Uint32Array;
  uvs?: Float64Array;
  attributes?: MeshAttribute[];
}

/**
 * What the API accepts as a mesh: the arrays may also be other typed arrays or plain number
 * arrays (copied; indices must be integers >= 0).
 */
export interface MeshLike {
  positions: ArrayLike<number>;
  triangles: ArrayLike<number>;
  uvs?: ArrayLike<number> | undefined;
  attributes?: { name: string; itemSize: number; perCorner?: boolean; values: ArrayLike<number> }[] | undefined;
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
  /** Keep OBJ `vt` as `uvs` when every used vertex has one value, else (uv seams) as the per-corner attribute 'uv'; default true. */
  readUvs?: boolean;
  /** OBJ `vn` as 'normal'; PLY colours as 'color' (in [0, 1]), nx/ny/nz as 'normal', every other scalar vertex property by its name; default true. */
  readAttributes?: boolean;
}

export interface ReadMeshResult extends Mesh {
  /** The format actually read. */
  format: MeshFormat;
  /** Non-fatal findings (welded vertices, skipped elements). */
  warnings: string[];
}

export interface WriteMeshOptions {
  /** OBJ: write `vt` when the mesh has uvs or a per-corner 'uv' attribute; PLY: u v, or the face list `texcoord`. Default true. */
  writeUvs?: boolean;
  /** OBJ: 'normal' as `vn`; PLY: every attribute as properties ('color' as uchar red green blue [alpha]). Default true. */
  writeAttributes?: boolean;
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

/**
 * A planar straight-line graph (Triangle's .poly contents).
 *   points          2·n numbers, x y per vertex (finite)
 *   segments        2·m vertex indices (0-based); optional (none: the convex hull is meshed)
 *   holes           2·h numbers: hole seed points (the region around a seed, bounded by segments, is removed)
 *   segmentMarkers  optional, one integer per segment, carried to the output edges
 * Exact duplicate points are merged; crossing or overlapping segments fail with InvalidPslg.
 */
export interface Pslg {
  points: Float64Array;
  segments?: Uint32Array;
  holes?: Float64Array;
  segmentMarkers?: Int32Array;
}

/** What refine2d accepts as a PSLG: other typed arrays or plain number arrays are copied. */
export interface PslgLike {
  points: ArrayLike<number>;
  segments?: ArrayLike<number> | undefined;
  holes?: ArrayLike<number> | undefined;
  segmentMarkers?: ArrayLike<number> | undefined;
}

/** Options of refine2d (sizes in the units of the input coordinates). */
export interface Refine2dOptions {
  /** Angle bound θ in degrees, [0, 34]; default 30. Every triangle that is not exempt gets min angle ≥ θ. */
  minAngle?: number;
  /** Largest triangle area (Triangle's -a); 0 (default): none. Not together with maxEdge. */
  maxArea?: number;
  /** Largest edge length; 0 (default): none. Not together with maxArea. */
  maxEdge?: number;
  /** Cap on Steiner vertices; reaching it throws ConformeshError 'IterationLimit' with the valid mesh so far as `error.result`. */
  maxInsertions?: number;
  /** Constrain the convex hull (Triangle's -c): the domain is the hull minus holes. Default false. */
  convexHull?: boolean;
  /** Domain by segment orientation: CCW loops bound the domain, CW loops inside them are holes. Default false. */
  holesByOrientation?: boolean;
  /** Off-centers (Üngör) instead of circumcenters; default true (fewer Steiner points). */
  offcenters?: boolean;
  /** Encroachment by diametral lenses instead of circles; default false. */
  diametralLens?: boolean;
}

/**
 * The refined triangulation.
 *   vertices       2·nV: the input points first (same order, unchanged), then Steiner vertices
 *   triangles      3·nT vertex indices, counter-clockwise
 *   edges          2·nE constrained edges (subsegments of input segments, hull edges with convexHull)
 *   edgeSegment    nE: input segment of each constrained edge (-1: a hull edge)
 *   edgeMarker     nE: that segment's marker (0 without markers)
 *   vertexSegment  nV: an input segment the vertex lies on, or -1
 *   vertexParam    nV: t with p = a + t·(b − a) on that segment (0 when vertexSegment is -1)
 */
export interface Refine2dResult {
  vertices: Float64Array;
  triangles: Uint32Array;
  edges: Uint32Array;
  edgeSegment: Int32Array;
  edgeMarker: Int32Array;
  vertexSegment: Int32Array;
  vertexParam: Float64Array;
  /** Smallest angle (degrees) over the triangles that are not exempt. */
  minAngle: number;
  /** Triangles below θ whose small angle is forced by the input (small input angles). */
  exemptTriangles: number;
  insertions: number;
  segmentSplits: number;
  rejected: number;
  seconds: number;
  /** 'Ok' in a returned result; 'IterationLimit' in the `result` of the error thrown when maxInsertions stopped the refinement. */
  status: StatusCodeName;
  message: string;
}

/** Options of flatten. */
export interface FlattenOptions {
  /**
   * 'circle' (default): a round disk, inner loops round holes. 'free': u = 0 on the outer loop.
   * 'corners': a straight-edged polygon keeping the angles of the outer loop's corners.
   */
  boundary?: 'circle' | 'free' | 'corners';
  /** 'corners': boundary vertices whose 3D angle differs from 180° by more than this (degrees) are corners; default 30. */
  cornerAngle?: number;
  /** Intrinsic Delaunay flips during the flow; default true. */
  flips?: boolean;
  /** Stop at max |K − K̄| ≤ tolerance (radians); default 1e-9. */
  tolerance?: number;
  /** Newton iteration cap (IterationLimit); default 100. */
  maxIterations?: number;
  /** 'circle': the Möbius-balanced solution; default true. */
  balanceMobius?: boolean;
  /** Fail with NumericalFailure when the layout is not valid (default true); false: report the counts. */
  requireValidLayout?: boolean;
}

/** The flattening's convergence and distortion report. */
export interface FlattenReport {
  iterations: number;
  /** Final max |K − K̄| (radians). */
  maxCurvatureError: number;
  /** max |K − K̄| before each Newton step, and at the end. */
  residuals: Float64Array;
  flips: number;
  euclideanFlips: number;
  seconds: number;
  secondsFlow: number;
  secondsLayout: number;
  secondsOverlay: number;
  /** |Σ K − 2π χ| of the target curvatures. */
  gaussBonnetError: number;
  invertedTriangles: number;
  boundaryCrossings: number;
  layoutLengthError: number;
  angleDistortionMean: number;
  angleDistortionMax: number;
  /** Input triangles inverted or degenerate in uv (exact orientation): a mesh written with `uv` has these; the layout may have none. */
  inputTrianglesInvertedInUv: number;
  areaDistortionMin: number;
  areaDistortionMax: number;
  areaDistortionRange: number;
  overlayCrossings: number;
  boundaryLoops: number;
  /** Corners used ('corners' boundary). */
  corners: number;
}

export interface FlattenResult {
  /** 2 per input vertex: the planar position of the vertex. */
  uv: Float64Array;
  /** Per input vertex: the log conformal scale factor (lengths scale by e^{(u_i+u_j)/2}). */
  u: Float64Array;
  /** The final intrinsic triangulation laid out in the plane (z = 0), for display. */
  layout: Mesh;
  /** Boundary loops (vertex indices), outer first, domain on the left. */
  boundaryLoops: Uint32Array[];
  report: FlattenReport;
}

/** Options of remesh (lengths absolute, angles in degrees). */
export interface RemeshOptions {
  /** Angle bound for every output triangle (3D), except at exempt corners; [0, 35], default 30. */
  minAngle?: number;
  /** Target edge length (absolute); < 0 (default -1): targetEdgeLengthRel × bounding-box diagonal. */
  targetEdgeLength?: number;
  /** Default 0.01. */
  targetEdgeLengthRel?: number;
  /** Chord deviation bound (absolute when ≥ 0; < 0, the default: chordToleranceRel × diagonal; 0: no curvature sizing). */
  chordTolerance?: number;
  /** Default 1e-3. */
  chordToleranceRel?: number;
  /**
   * Error-driven remeshing: the largest two-sided Hausdorff distance to the input (absolute when
   * > 0; < 0, the default -1: maxErrorRel × diagonal, off when that is 0; 0: off). Sizes grow as large as it
   * allows and every sharp edge is a crease (minFeatureLength defaults to 0); the target edge
   * length then only scales the cuts and the smallest edge.
   * The report's hausdorffRel is within it, else the call fails with IterationLimit.
   */
  maxError?: number;
  /** maxError as a fraction of the bounding-box diagonal; default 0 (off). */
  maxErrorRel?: number;
  /** Neighbouring edge length ratio bound (> 1); default 1.5. */
  gradation?: number;
  /** Edge length clamps (absolute; < 0: target/10 and target). */
  minEdgeLength?: number;
  /** See minEdgeLength. */
  maxEdgeLength?: number;
  /** Dihedral angle above which edges are features; default 40. */
  featureAngle?: number;
  /** Turning angle of a feature curve that makes a corner; default 50. */
  cornerTurn?: number;
  /** Sharp edges are creases only in chains that stand out of their neighbourhood and are at least
   *  this long, or that stand out strongly or bridge two curves: the facets of a coarse or noisy
   *  surface are not creases (absolute; < 0 or absent: twice the target edge length; 0: keep every
   *  sharp edge). */
  minFeatureLength?: number;
  /** Patches narrower than this (2·area / perimeter) are merged into a neighbour, dropping the sharp
   *  edges between them (absolute; < 0: half the sizing's smallest edge, target/20 by default;
   *  0 or absent: keep every patch and every sharp edge). */
  minPatchWidth?: number;
  /** A patch whose scale factor ratio exceeds this is split; default 50. */
  maxScaleRatio?: number;
  /** Cap on the rounds of the 3D angle certificate (they also stop after two rounds in a row without a gain); default 6. */
  maxCertificateRounds?: number;
  /** Optimize each patch after refinement (ODT moves and flips judged in 3D; default true). */
  optimize?: boolean;
  /**
   * Hold the chord tolerance at cone tips too (a vertex whose neighbours lie far off its tangent
   * plane: the output cuts such a tip off in proportion to the size, not its square). Default
   * false (error-driven remeshing cuts the sizes where an attempt exceeded its bound instead).
   */
  coneTips?: boolean;
  /**
   * A crease that ends inside a smooth region stays a constrained polyline inside its patch's
   * planar domain, instead of being continued until it closes the region off. Default true.
   */
  innerCreases?: boolean;
  /** The boundary condition each patch's flattening tries first (the others follow when its layout fails). Default 'free'. */
  boundary?: 'free' | 'corners' | 'circle';
  /** Return every patch in the plane (RemeshResult.patches, patchOfTriangle), e.g. to draw the flattened domain. Default false. */
  patches?: boolean;
  /**
   * Carry the input's uvs and attributes to the output (default true): edges where a per-corner
   * attribute jumps (uv seams) are kept as feature curves, so no triangle straddles one and texture
   * charts stay whole, and every output corner gets the input's values interpolated at its point on
   * the input (RemeshResult.surfacePoints), on its triangle's side of a seam. Per-vertex attributes
   * stay per vertex, per-corner ones per corner; normals are renormalized.
   */
  attributes?: boolean;
  /** Return RemeshResult.surfacePoints even for an input without attributes. Default false. */
  surfacePoints?: boolean;
  /** Optimization passes (hard cap, default 2; each pass costs about as much as the lift). */
  optimizeIterations?: number;
  /** Stop when a pass gains less than this fraction of the mean min angle (default 1e-3). */
  optimizeTolerance?: number;
  /**
   * Threads over the patches and the report's distances, an integer in [0, 1024]; 0 (default) the
   * hardware's concurrency. The output is the same for every count. In WebAssembly, the threaded
   * build (cross-origin isolated pages: InitOptions.threads) runs on up to its pool's threads; the
   * single-threaded build (elsewhere, and in Node) accepts the option and runs on one.
   */
  threads?: number;
  /** Sampled two-sided Hausdorff distance in the report; default true. */
  computeHausdorff?: boolean;
  hausdorffSamples?: number;
  /** Per-input-vertex target edge length (absolute), one per input vertex. */
  vertexSizing?: ArrayLike<number>;
  /** User feature edges: 2 input vertex indices per edge. */
  featureEdges?: ArrayLike<number>;
  /**
   * Output limits. The output size and peak memory are predicted from the sizing field before
   * flattening and refinement, and the real counts checked after refinement: above a limit the call
   * fails with `ConformeshError` code 'TooLarge' (message: the estimate or count and the limit).
   * 0 is 'InvalidArgument', not "no limit": pass a huge number to lift one.
   * Defaults: maxTriangles 33554432 (32 Mi), maxVertices 16777216 (16 Mi), maxMemoryBytes 3 GiB.
   */
  maxTriangles?: number;
  maxVertices?: number;
  maxMemoryBytes?: number;
  /**
   * The output must have the input's components, boundary loops and Euler characteristic, and no
   * non-manifold edge or vertex; otherwise remesh throws `ConformeshError` code 'InternalError'
   * (stage 'report'; the message says what differs). true (default false): the error carries the
   * defective output as `error.result` (mesh, report, patches), to inspect the defect.
   */
  keepDefectiveOutput?: boolean;
  /** For testing the check above: break the output (one edge gets a third triangle) so that it fails. Default false. */
  forceTopologyDefect?: boolean;
}

/** An input corner whose angle is below the bound: the output triangles touching it, or with an edge across its small wedge, are exempt. */
export interface ExemptCorner {
  vertex: number;
  outputVertex: number;
  angle: number;
  /** The exempt triangles: touching the corner, or across its wedge (both ends on the two curves meeting there). */
  triangles: Uint32Array;
}

/** The remesh quality report (what `conformesh remesh --json` prints, and more). */
export interface RemeshReport {
  inputTriangles: number;
  inputVertices: number;
  triangles: number;
  vertices: number;
  minAngle: number;
  maxAngle: number;
  meanMinAngle: number;
  pctBelow20: number;
  pctBelow26: number;
  pctBelow30: number;
  /** % of triangles whose smallest angle is ≥ 40°, ≥ 50°. */
  pctMinAtLeast40: number;
  pctMinAtLeast50: number;
  minAngleOutsideExempt: number;
  trianglesBelowBoundOutsideExempt: number;
  exemptCorners: ExemptCorner[];
  /** Two-sided, relative to the input bounding-box diagonal (-1: not computed). */
  hausdorffRel: number;
  maxDistanceToInputRel: number;
  meanEdgeLength: number;
  targetEdgeLength: number;
  delaunayFraction: number;
  featureCurves: number;
  featureCurvesKept: number;
  sharpEdges: number;
  cutEdges: number;
  /** Sharp edges (above featureAngle) found not to be creases (see minFeatureLength). */
  droppedFeatureEdges: number;
  /** Input edges kept as feature curves for being attribute seams (the `attributes` option). */
  seamEdges: number;
  patches: number;
  curves: number;
  curveSamples: number;
  flowIterations: number[];
  patchSplitsForScale: number;
  /** Patches cut in two through the point where their flattening's scale sank (a finger tip). */
  sinkCuts: number;
  /** Narrow patches joined to a neighbour once every patch was flattened (the joins kept). */
  patchJoins: number;
  conformingRounds: number;
  certificateRounds: number;
  /** Vertex moves and edge flips accepted by the optimization. */
  optimizeMoves: number;
  optimizeFlips: number;
  /** Vertices the optimization added where its moves and flips left a triangle below the bound. */
  optimizeSplits: number;
  /** Edges the optimization collapsed toward regular vertex valences (above a 30° bound). */
  optimizeCollapses: number;
  /** Free vertices moved over the surface where the 3D angle certificate left a triangle below the bound. */
  repairMoves: number;
  /** Output triangles predicted from the sizing field and the flattened patches' widths before refinement (the prediction from the first segmentation is checked against maxTriangles). */
  estimatedTriangles: number;
  /** The topology check passed (false only in the result of an error, with keepDefectiveOutput). */
  topologyPreserved: boolean;
  /** Wall seconds per stage, in the order remesh() runs them (STAGES), and in all. */
  seconds: StageSeconds;
  warnings: string[];
}

/** One patch in the plane (with the `patches` option). */
export interface RemeshPatch {
  id: number;
  /** The flattened input patch: planar positions (2 per vertex), its triangles, the input triangle of each, and the log scale factor u per vertex. */
  layout: { uv: Float64Array; triangles: Uint32Array; inputFace: Uint32Array; factor: Float64Array };
  /** The refined planar mesh: positions (2 per vertex), triangles (the patch's output triangles, same order) and the output vertex of each planar vertex. */
  refined: { uv: Float64Array; triangles: Uint32Array; outputVertex: Uint32Array };
}

export interface RemeshResult {
  mesh: Mesh;
  report: RemeshReport;
  /** With the `patches` option: every patch in the plane. */
  patches?: RemeshPatch[];
  /** With the `patches` option: the patch of every output triangle. */
  patchOfTriangle?: Uint32Array;
  /**
   * With attributes carried or the `surfacePoints` option: every output corner's point on the
   * input (corner c of triangle t is 3·t + c): `face` the input triangle its vertex lies on (on the
   * triangle's side of a seam), `barycentric` 3 coordinates per corner w.r.t. that triangle's
   * corners (they sum to 1 and weight its vertices to the output vertex, up to rounding).
   */
  surfacePoints?: { face: Uint32Array; barycentric: Float64Array };
}
