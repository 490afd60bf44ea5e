// The remesh options and report as seen from TypeScript. The single definition is the C++ table
// (include/conformesh/remesh_schema.h), exported by the module as remeshSchema(): the package CLI takes its remesh
// flags, help, defaults and JSON from it. The key lists here exist so that the TypeScript types can
// be checked: `satisfies` makes tsc fail when a key of RemeshOptions or RemeshReport is missing
// here or one here is not in the type, and tests/js/schema.test.ts checks these lists against the
// module's export and both CLIs' help and JSON.
import type { ExemptCorner, RemeshOptions, RemeshReport } from './types.js';

/** How an option's value is read: a number, an integer, a count (saturating), a switch, a boundary name. */
export type OptionKind = 'number' | 'integer' | 'count' | 'boolean' | 'boundary';

/** One row of the C++ option table. */
export interface OptionRow {
  name: string;
  kind: OptionKind;
  default: number | boolean | string;
  /** The range the module accepts. */
  lo: number;
  hi: number;
  /** The CLI flag ('' for an option only the library API has); a boolean's '--no-' flag sets false. */
  flag: string;
  /** What the flag's value is, as --help shows it ('DEG'); '' for a switch. */
  value: string;
  help: string;
}

/** The module's remeshSchema(): the option rows and the report's field names, in the C++ order. */
export interface RemeshSchema {
  options: OptionRow[];
  report: string[];
  exemptCorner: string[];
}

/** The options of the table: every key of RemeshOptions but the per-element inputs (passed apart). */
type TableOption = Exclude<keyof RemeshOptions, 'vertexSizing' | 'featureEdges'>;

const keys = <K extends string>(record: Record<K, 1>) => Object.keys(record) as K[];

/** Every option of the C++ table, by name. */
export const REMESH_OPTION_KEYS = keys({
  minAngle: 1, targetEdgeLength: 1, targetEdgeLengthRel: 1, chordTolerance: 1, chordToleranceRel: 1, maxError: 1,
  maxErrorRel: 1, gradation: 1, minEdgeLength: 1, maxEdgeLength: 1, featureAngle: 1, cornerTurn: 1, minFeatureLength: 1,
  minPatchWidth: 1, innerCreases: 1, coneTips: 1, boundary: 1, maxScaleRatio: 1, maxCertificateRounds: 1, optimize: 1, optimizeIterations: 1,
  optimizeTolerance: 1, patches: 1, attributes: 1, surfacePoints: 1, computeHausdorff: 1, hausdorffSamples: 1,
  threads: 1, maxVertices: 1, maxTriangles: 1, maxMemoryBytes: 1, keepDefectiveOutput: 1, forceTopologyDefect: 1,
} satisfies Record<TableOption, 1>);

/** Every field of the report, by name. */
export const REMESH_REPORT_KEYS = keys({
  inputTriangles: 1, inputVertices: 1, triangles: 1, vertices: 1, minAngle: 1, maxAngle: 1, meanMinAngle: 1,
  pctBelow20: 1, pctBelow26: 1, pctBelow30: 1, pctMinAtLeast40: 1, pctMinAtLeast50: 1, minAngleOutsideExempt: 1,
  trianglesBelowBoundOutsideExempt: 1, exemptCorners: 1, hausdorffRel: 1, maxDistanceToInputRel: 1,
  meanEdgeLength: 1, targetEdgeLength: 1, delaunayFraction: 1, featureCurves: 1, featureCurvesKept: 1,
  sharpEdges: 1, cutEdges: 1, droppedFeatureEdges: 1, seamEdges: 1, patches: 1, curves: 1, curveSamples: 1,
  flowIterations: 1, patchSplitsForScale: 1, sinkCuts: 1, patchJoins: 1, conformingRounds: 1, certificateRounds: 1, optimizeMoves: 1,
  optimizeFlips: 1, optimizeSplits: 1, optimizeCollapses: 1, repairMoves: 1, estimatedTriangles: 1, topologyPreserved: 1, seconds: 1, warnings: 1,
} satisfies Record<keyof RemeshReport, 1>);

/** Every field of an exempt corner, by name. */
export const EXEMPT_CORNER_KEYS = keys({ vertex: 1, outputVertex: 1, angle: 1, triangles: 1 } satisfies Record<
  keyof ExemptCorner,
  1
>);
