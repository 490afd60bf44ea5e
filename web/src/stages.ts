// The remesh progress bars. The library reports (stage, fraction) with fraction the progress of
// the whole call: bindings/remesh.cpp overallProgress gives each stage an interval of [0, 1], and
// the calls are made in pipeline order (src/remesh/remesh.cpp Pipeline::run). A bar shows its
// stage's own progress, 0 -> 100 % over the stage's interval.

export interface StageBar {
  /** The library's stage name (ProgressEvent.stage). */
  stage: string;
  /** What the bar covers, for its tooltip. */
  title: string;
  /** The stage's interval of the overall fraction (bindings/remesh.cpp overallProgress). */
  lo: number;
  hi: number;
}

/**
 * In pipeline order. 'lift' and 'stitch' have intervals in overallProgress but never report: the
 * lift and the optimization run inside each patch's refinement, and stitching inside the
 * refinement's certificate rounds. They get no bar of their own (refine reaches 0.85, then the
 * report's single event is 1).
 */
export const STAGE_BARS: readonly StageBar[] = [
  { stage: 'validate', title: 'check and repair the input', lo: 0.0, hi: 0.02 },
  { stage: 'segment', title: 'feature curves, cuts into disk patches, sizing field', lo: 0.02, hi: 0.1 },
  { stage: 'flatten', title: 'conformal flattening of every patch', lo: 0.1, hi: 0.45 },
  { stage: 'curve-mesh', title: 'samples along the feature and cut curves', lo: 0.45, hi: 0.5 },
  { stage: 'refine', title: 'planar Delaunay refinement per patch, with the lift to 3D, the optimization and the stitching (certificate rounds)', lo: 0.5, hi: 0.85 },
  { stage: 'report', title: 'quality report (angles, distances, topology)', lo: 0.96, hi: 1.0 },
];

/** A stage's own progress in [0, 1] from the call's overall fraction. */
export function stageFraction(bar: StageBar, overall: number): number {
  const f = (overall - bar.lo) / (bar.hi - bar.lo);
  return Math.min(1, Math.max(0, Number.isFinite(f) ? f : 0));
}

/** One bar's value as shown, in the order shown (for the end-to-end test). */
export interface BarUpdate {
  stage: string;
  value: number;
}

/**
 * Bar values from the events of one call: an event of stage k sets bar k to its own fraction
 * (never backwards) and completes the bars before k (that stage has ended). Events of stages
 * without a bar are ignored. Returns the bar updates it made.
 */
export class StageProgress {
  readonly values: number[] = STAGE_BARS.map(() => 0);

  reset(): void {
    this.values.fill(0);
  }

  update(stage: string, overall: number): BarUpdate[] {
    const k = STAGE_BARS.findIndex((b) => b.stage === stage);
    if (k < 0) return [];
    const changed: BarUpdate[] = [];
    for (let j = 0; j < k; ++j) {
      if (this.values[j]! < 1) {
        this.values[j] = 1;
        changed.push({ stage: STAGE_BARS[j]!.stage, value: 1 });
      }
    }
    const v = Math.max(this.values[k]!, stageFraction(STAGE_BARS[k]!, overall));
    this.values[k] = v;
    changed.push({ stage, value: v });
    return changed;
  }
}
