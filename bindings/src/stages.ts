// The pipeline stages as seen from JavaScript, in the order remesh() runs them. The single
// definition is the C++ table (include/conformesh/stages.h); this copy exists so that stage names and the
// report's seconds can be types, and tests/js/stages.test.ts checks it row by row against the
// module's stageTable() export. Stage, the report's seconds, the CLI's report and the demo page's
// bars and time rows come from it.

/**
 * One stage: `name` as errors and progress events give it, `key` of its seconds in the report,
 * `label` for people, `weight` its share (percent) of a typical remesh's progress, `timed`
 * whether remesh() runs it (and the report gives its seconds).
 */
export interface StageRow {
  readonly name: string;
  readonly key: string;
  readonly label: string;
  readonly weight: number;
  readonly timed: boolean;
}

/** Every stage, in the C++ table's order: a stage's numeric value is its index. */
export const STAGES = [
  { name: 'read', key: 'read', label: 'read', weight: 0, timed: false },
  { name: 'validate', key: 'validate', label: 'check input', weight: 1, timed: true },
  { name: 'precondition', key: 'precondition', label: 'precondition', weight: 0, timed: true },
  { name: 'segment', key: 'segment', label: 'segment', weight: 25, timed: true },
  { name: 'flatten', key: 'flatten', label: 'flatten', weight: 30, timed: true },
  { name: 'curve-mesh', key: 'curveMesh', label: 'curves', weight: 1, timed: true },
  { name: 'refine', key: 'refine', label: 'refine', weight: 20, timed: true },
  { name: 'lift', key: 'lift', label: 'lift to 3D', weight: 0, timed: true },
  { name: 'optimize', key: 'optimize', label: 'optimize', weight: 8, timed: true },
  { name: 'stitch', key: 'stitch', label: 'stitch', weight: 1, timed: true },
  { name: 'certificate', key: 'certificate', label: 'angle check', weight: 5, timed: true },
  { name: 'repair', key: 'repair', label: 'repair', weight: 1, timed: true },
  { name: 'report', key: 'report', label: 'report', weight: 8, timed: true },
  { name: 'write', key: 'write', label: 'write', weight: 0, timed: false },
  { name: 'api', key: 'api', label: 'call', weight: 0, timed: false },
] as const satisfies readonly StageRow[];

type Row = (typeof STAGES)[number];
/** Name of a pipeline stage, e.g. `'flatten'`. */
export type StageName = Row['name'];
/** A stage remesh() runs. */
export type RemeshStageRow = Extract<Row, { timed: true }>;
/** Wall seconds per stage remesh() runs (by its key), and for the whole call. */
export type StageSeconds = { [K in RemeshStageRow['key']]: number } & { total: number };

/** Pipeline stages by name, with their numeric values (as C++ `conformesh::Stage`). */
export const Stage = Object.fromEntries(STAGES.map((s, i) => [s.name, i])) as { readonly [K in StageName]: number };

/** The stages remesh() runs, in its order: those whose seconds the report gives. */
export const REMESH_STAGES: readonly RemeshStageRow[] = STAGES.filter((s): s is RemeshStageRow => s.timed);

/** Stage name for a numeric stage (progress callbacks receive numbers from C++). */
export function stageName(value: number): StageName {
  return STAGES[value]?.name ?? 'api';
}

export function isStageName(x: unknown): x is StageName {
  return typeof x === 'string' && STAGES.some((s) => s.name === x);
}

/**
 * The interval of a remesh's overall progress (ProgressEvent.fraction, 0 to 1) over which this
 * stage's own progress runs: the weights before it, and with it, over all the weights.
 */
export function stageInterval(name: StageName): { lo: number; hi: number } {
  const i = STAGES.findIndex((s) => s.name === name);
  let before = 0;
  let total = 0;
  STAGES.forEach((s, j) => {
    if (j < i) before += s.weight;
    total += s.weight;
  });
  return { lo: before / total, hi: (before + STAGES[i]!.weight) / total };
}
