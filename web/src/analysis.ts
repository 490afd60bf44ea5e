// Client of analysis.worker.ts: the page's geometry analysis off the main thread.
import type { AngleStats, Bounds, FeaturePreview } from './geometry.ts';

export interface AnalysisRequest {
  id: number;
  positions: Float64Array;
  triangles: Uint32Array;
  /** Compute triangle angles and their statistics. */
  angles: boolean;
  /** Compute the feature preview at this feature angle (degrees). */
  featureAngle?: number;
}

export interface AnalysisResult {
  bounds: Bounds;
  angles?: Float64Array;
  stats?: AngleStats;
  preview?: FeaturePreview;
}

export class Analyzer {
  private readonly worker = new Worker(new URL('./analysis.worker.ts', import.meta.url), { type: 'module' });
  private readonly pending = new Map<number, { resolve: (r: AnalysisResult) => void; reject: (e: Error) => void }>();
  private nextId = 1;

  constructor() {
    this.worker.onmessage = (ev: MessageEvent<{ id: number; result?: AnalysisResult; error?: string }>) => {
      const p = this.pending.get(ev.data.id);
      if (!p) return;
      this.pending.delete(ev.data.id);
      if (ev.data.result) p.resolve(ev.data.result);
      else p.reject(new Error(`page analysis failed: ${ev.data.error}`));
    };
    this.worker.onerror = (ev) => {
      for (const p of this.pending.values()) p.reject(new Error(`page analysis worker failed: ${ev.message}`));
      this.pending.clear();
    };
  }

  /** Analyse a mesh (its arrays are copied to the worker, not transferred). */
  analyze(mesh: { positions: Float64Array; triangles: Uint32Array }, options: { angles: boolean; featureAngle?: number }): Promise<AnalysisResult> {
    const id = this.nextId++;
    const request: AnalysisRequest = { id, positions: mesh.positions, triangles: mesh.triangles, angles: options.angles };
    if (options.featureAngle !== undefined) request.featureAngle = options.featureAngle;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.worker.postMessage(request);
    });
  }
}
