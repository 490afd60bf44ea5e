// A page worker for the page's own per-mesh analysis (triangle angles, their statistics, the
// feature/patch preview), so loading a big mesh does not freeze the page.
import { angleStats, bounds, featurePreview, triangleAngles } from './geometry.ts';
import type { AnalysisRequest, AnalysisResult } from './analysis.ts';

interface Scope {
  onmessage: ((ev: MessageEvent<AnalysisRequest>) => void) | null;
  postMessage(message: unknown, transfer: Transferable[]): void;
}
const scope = globalThis as unknown as Scope;

scope.onmessage = (ev) => {
  const { id, positions, triangles, featureAngle, angles: wantAngles } = ev.data;
  try {
    const mesh = { positions, triangles };
    const result: AnalysisResult = { bounds: bounds(positions) };
    const transfer: ArrayBuffer[] = [];
    if (wantAngles) {
      const angles = triangleAngles(mesh);
      result.angles = angles;
      result.stats = angleStats(angles);
      transfer.push(angles.buffer as ArrayBuffer);
    }
    if (featureAngle !== undefined) {
      result.preview = featurePreview(mesh, featureAngle);
      transfer.push(result.preview.featureEdges.buffer as ArrayBuffer, result.preview.patchOfFace.buffer as ArrayBuffer);
    }
    scope.postMessage({ id, result }, transfer);
  } catch (e) {
    scope.postMessage({ id, error: e instanceof Error ? e.message : String(e) }, []);
  }
};
