// The remesh stage bars. The stages come from the library: those its progress events name, and
// those whose times its report gives (report.seconds); a stage is one bar whichever of the two
// names it ('curve-mesh' / 'curveMesh', quality.ts stageKey). The library reports (stage,
// fraction) with fraction the progress of the whole call, each stage's own progress over its
// interval of [0, 1] (the package's stageInterval), and a bar shows its stage's own progress,
// 0 -> 100 % over that interval. After the call every bar is full and shows the stage's time.
import { STAGES, stageInterval } from 'conformesh';
import { stageKey } from './quality.ts';

/** A stage's own progress in [0, 1] from the call's overall fraction (undefined: it reports none). */
export function stageFraction(stage: string, overall: number): number | undefined {
  const row = STAGES.find((s) => stageKey(s.name) === stageKey(stage));
  if (!row || row.weight === 0) return undefined;
  const i = stageInterval(row.name);
  const f = (overall - i.lo) / (i.hi - i.lo);
  return Math.min(1, Math.max(0, Number.isFinite(f) ? f : 0));
}

/** One bar's value as shown, in the order shown (for the end-to-end test). */
export interface BarUpdate {
  /** stageKey of the stage. */
  stage: string;
  value: number;
}

/**
 * Bar values of one call. The bars are in the library's order: that of the last report's times,
 * with a stage first seen in an event added at the end. An event of stage k sets bar k to its own
 * fraction (never backwards; a stage without an interval shows no fraction until it ends) and
 * completes the bars before k (those stages have ended).
 */
export class StageProgress {
  /** stageKey of every bar, in order, and the library name it was first seen under. */
  readonly order: string[] = [];
  readonly names = new Map<string, string>();
  readonly values = new Map<string, number>();

  /** Add the bars of these stages (library names), in this order, before any stage added later. */
  adopt(stages: readonly string[]): string[] {
    const added: string[] = [];
    let at = 0;
    for (const name of stages) {
      const key = stageKey(name);
      const i = this.order.indexOf(key);
      if (i >= 0) {
        at = Math.max(at, i + 1);
        continue;
      }
      this.order.splice(at++, 0, key);
      this.names.set(key, name);
      this.values.set(key, 0);
      added.push(key);
    }
    return added;
  }

  reset(): void {
    for (const k of this.order) this.values.set(k, 0);
  }

  update(stage: string, overall: number): BarUpdate[] {
    const key = stageKey(stage);
    if (!this.values.has(key)) this.adopt([...this.order.map((k) => this.names.get(k)!), stage]);
    const k = this.order.indexOf(key);
    const changed: BarUpdate[] = [];
    for (let j = 0; j < k; ++j) {
      const before = this.order[j]!;
      if (this.values.get(before)! < 1) {
        this.values.set(before, 1);
        changed.push({ stage: before, value: 1 });
      }
    }
    const own = stageFraction(stage, overall);
    const v = Math.max(this.values.get(key)!, own ?? 0);
    this.values.set(key, v);
    changed.push({ stage: key, value: v });
    return changed;
  }

  /** The call has ended: every bar full. */
  finish(): BarUpdate[] {
    const changed: BarUpdate[] = [];
    for (const key of this.order) {
      if (this.values.get(key)! < 1) {
        this.values.set(key, 1);
        changed.push({ stage: key, value: 1 });
      }
    }
    return changed;
  }
}
