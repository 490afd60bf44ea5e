// Attributes carried through remesh (issue 22): a synthetic plane with two texture charts and
// spot.obj (uv seams): every output corner's uv is the input's interpolated at its point on the
// input, no triangle straddles a seam, the writers and conformesh/three keep them.
import { describe, expect, it } from 'vitest';
import { init, type Mesh, type MeshAttribute, type RemeshResult } from '../../dist/index.js';
import { toBufferGeometry } from '../../dist/three.js';
import { dataFile } from './helpers.js';

/** An n×n grid on [0,1]² (z = 0); uv per corner (x, y) left of x = 1/2 and (x + 10, y) right of it; a per-vertex value 2x + 3y. */
function twoChartPlane(n: number): Mesh {
  const positions: number[] = [];
  const triangles: number[] = [];
  const uv: number[] = [];
  for (let j = 0; j <= n; ++j) for (let i = 0; i <= n; ++i) positions.push(i / n, j / n, 0);
  for (let j = 0; j < n; ++j)
    for (let i = 0; i < n; ++i) {
      const a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      for (const v of [a, b, d, a, d, c]) {
        triangles.push(v);
        uv.push(positions[3 * v]! + (2 * i >= n ? 10 : 0), positions[3 * v + 1]!);
      }
    }
  const value = new Float64Array(positions.length / 3).map((_, v) => 2 * positions[3 * v]! + 3 * positions[3 * v + 1]!);
  return {
    positions: Float64Array.from(positions),
    triangles: Uint32Array.from(triangles),
    attributes: [
      { name: 'uv', itemSize: 2, perCorner: true, values: Float64Array.from(uv) },
      { name: 'value', itemSize: 1, perCorner: false, values: value },
    ],
  };
}

/** Triangles of a mesh on the plane with corners on both sides of x = 1/2. */
function straddling(m: Mesh): number {
  let n = 0;
  for (let t = 0; t < m.triangles.length / 3; ++t) {
    const xs = [0, 1, 2].map((c) => m.positions[3 * m.triangles[3 * t + c]!]!);
    n += xs.every((x) => x <= 0.5 + 1e-12) || xs.every((x) => x >= 0.5 - 1e-12) ? 0 : 1;
  }
  return n;
}

function attribute(m: Mesh, name: string): MeshAttribute {
  const a = m.attributes?.find((x) => x.name === name);
  if (!a) throw new Error(`no attribute ${name}`);
  return a;
}

/** Largest |output corner uv − input uv interpolated at the corner's surface point| and |point − vertex|. */
function interpolationError(input: Mesh, r: RemeshResult): { uv: number; position: number } {
  const inUv = attribute(input, 'uv');
  const outUv = attribute(r.mesh, 'uv');
  const sp = r.surfacePoints!;
  let uv = 0, position = 0;
  for (let c = 0; c < r.mesh.triangles.length; ++c) {
    const f = sp.face[c]!;
    const p = [0, 0, 0], q = [0, 0];
    for (let k = 0; k < 3; ++k) {
      const w = sp.barycentric[3 * c + k]!;
      const v = input.triangles[3 * f + k]!;
      for (let i = 0; i < 3; ++i) p[i]! += w * input.positions[3 * v + i]!;
      for (let i = 0; i < 2; ++i) q[i]! += w * inUv.values[2 * (3 * f + k) + i]!;
    }
    const v = r.mesh.triangles[c]!;
    position = Math.max(position, Math.hypot(p[0]! - r.mesh.positions[3 * v]!, p[1]! - r.mesh.positions[3 * v + 1]!, p[2]! - r.mesh.positions[3 * v + 2]!));
    uv = Math.max(uv, Math.abs(q[0]! - outUv.values[2 * c]!), Math.abs(q[1]! - outUv.values[2 * c + 1]!));
  }
  return { uv, position };
}

describe('attributes carried through remesh', () => {
  it('a plane with two texture charts: every triangle on one side of the seam, uv its chart\'s at each corner', async () => {
    const cm = await init();
    const input = twoChartPlane(8);
    const r = cm.remesh(input, { targetEdgeLengthRel: 0.03 });
    expect(r.report.seamEdges).toBe(8);
    const uv = attribute(r.mesh, 'uv');
    expect(uv.perCorner).toBe(true);
    const P = r.mesh.positions, T = r.mesh.triangles;
    let worst = 0;
    for (let t = 0; t < T.length / 3; ++t) {
      const xs = [0, 1, 2].map((c) => P[3 * T[3 * t + c]!]!);
      const offset = xs.reduce((a, b) => a + b) / 3 > 0.5 ? 10 : 0;
      for (let c = 0; c < 3; ++c) {
        const v = T[3 * t + c]!;
        worst = Math.max(worst, Math.abs(uv.values[2 * (3 * t + c)]! - P[3 * v]! - offset), Math.abs(uv.values[2 * (3 * t + c) + 1]! - P[3 * v + 1]!));
      }
    }
    expect(straddling(r.mesh)).toBe(0);
    expect(worst).toBeLessThanOrEqual(1e-9);
    const value = attribute(r.mesh, 'value');
    expect(value.perCorner).toBe(false);
    for (let v = 0; v < P.length / 3; ++v) expect(Math.abs(value.values[v]! - 2 * P[3 * v]! - 3 * P[3 * v + 1]!)).toBeLessThanOrEqual(1e-9);
    expect(interpolationError(input, r).uv).toBeLessThanOrEqual(1e-9);
    // without: nothing carried, no seam kept
    const plain = cm.remesh(input, { targetEdgeLengthRel: 0.03, attributes: false });
    expect(plain.mesh.attributes).toBeUndefined();
    expect(plain.report.seamEdges).toBe(0);
    expect(straddling(plain.mesh)).toBeGreaterThan(0); // the check above sees triangles across x = 1/2
  });

  it('spot.obj: uv at each corner = the input uv interpolated at its pull-back point; OBJ and three.js keep them', async () => {
    const cm = await init();
    const input = cm.readMesh(dataFile('spot.obj'));
    expect(attribute(input, 'uv').perCorner).toBe(true);
    const r = cm.remesh(input);
    expect(r.report.seamEdges).toBeGreaterThan(0);
    expect(r.report.trianglesBelowBoundOutsideExempt).toBe(0);
    const diag = Math.hypot(...[0, 1, 2].map((k) => {
      let lo = Infinity, hi = -Infinity;
      for (let i = k; i < input.positions.length; i += 3) (lo = Math.min(lo, input.positions[i]!)), (hi = Math.max(hi, input.positions[i]!));
      return hi - lo;
    }));
    const err = interpolationError(input, r);
    expect(err.uv).toBeLessThanOrEqual(1e-9);
    expect(err.position).toBeLessThanOrEqual(1e-9 * diag);
    // OBJ round trip: the same uv at every corner (the writer shares one vt per distinct value)
    const back = cm.readMesh(cm.writeMesh(r.mesh, 'obj'), 'obj');
    expect(Array.from(attribute(back, 'uv').values)).toEqual(Array.from(attribute(r.mesh, 'uv').values));
    // three.js: vertices split at the seams, each corner's uv as float32, positions those of the mesh vertex
    const g = toBufferGeometry(r.mesh);
    const index = g.getIndex()!.array, gUv = g.getAttribute('uv'), gPos = g.getAttribute('position');
    const meshVertex = g.userData.meshVertex as Uint32Array;
    expect(gUv.count).toBeGreaterThan(r.mesh.positions.length / 3);
    const outUv = attribute(r.mesh, 'uv').values;
    let wrong = 0;
    for (let c = 0; c < index.length; ++c) {
      const gv = index[c]!, v = r.mesh.triangles[c]!;
      const ok =
        meshVertex[gv] === v &&
        gUv.getX(gv) === Math.fround(outUv[2 * c]!) &&
        gUv.getY(gv) === Math.fround(outUv[2 * c + 1]!) &&
        gPos.getX(gv) === Math.fround(r.mesh.positions[3 * v]!);
      wrong += ok ? 0 : 1;
    }
    expect(wrong).toBe(0);
  });
});
