// Small geometry helpers of the page: triangle angles, edge adjacency, and the feature-edge /
// patch preview shown on the input before the library has segmented it.
import type { MeshLike } from 'conformesh';

export interface Bounds {
  min: [number, number, number];
  max: [number, number, number];
  diagonal: number;
}

export function bounds(positions: ArrayLike<number>): Bounds {
  const min: [number, number, number] = [Infinity, Infinity, Infinity];
  const max: [number, number, number] = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < positions.length; i += 3) {
    for (let k = 0; k < 3; ++k) {
      const v = positions[i + k]!;
      if (v < min[k]!) min[k] = v;
      if (v > max[k]!) max[k] = v;
    }
  }
  const d = Math.hypot(max[0] - min[0], max[1] - min[1], max[2] - min[2]);
  return { min, max, diagonal: Number.isFinite(d) ? d : 0 };
}

/** The three corner angles (degrees) of every triangle: 3·nF values, corner order a, b, c. */
export function triangleAngles(mesh: MeshLike): Float64Array {
  const p = mesh.positions;
  const t = mesh.triangles;
  const out = new Float64Array(t.length);
  const toDeg = 180 / Math.PI;
  for (let f = 0; f < t.length; f += 3) {
    const a = 3 * t[f]!, b = 3 * t[f + 1]!, c = 3 * t[f + 2]!;
    const ab = Math.hypot(p[b]! - p[a]!, p[b + 1]! - p[a + 1]!, p[b + 2]! - p[a + 2]!);
    const bc = Math.hypot(p[c]! - p[b]!, p[c + 1]! - p[b + 1]!, p[c + 2]! - p[b + 2]!);
    const ca = Math.hypot(p[a]! - p[c]!, p[a + 1]! - p[c + 1]!, p[a + 2]! - p[c + 2]!);
    // law of cosines, clamped; degenerate triangles give NaN-free 0/180 angles
    const ang = (opp: number, s1: number, s2: number) => {
      if (s1 === 0 || s2 === 0) return 0;
      return Math.acos(Math.min(1, Math.max(-1, (s1 * s1 + s2 * s2 - opp * opp) / (2 * s1 * s2)))) * toDeg;
    };
    out[f] = ang(bc, ab, ca);
    out[f + 1] = ang(ca, ab, bc);
    out[f + 2] = ang(ab, bc, ca);
  }
  return out;
}

/** Per-triangle minimum angle (degrees). */
export function minAnglePerTriangle(angles: Float64Array): Float64Array {
  const out = new Float64Array(angles.length / 3);
  for (let f = 0; f < out.length; ++f) out[f] = Math.min(angles[3 * f]!, angles[3 * f + 1]!, angles[3 * f + 2]!);
  return out;
}

export interface AngleStats {
  min: number;
  max: number;
  meanMin: number;
  below20: number;
  below30: number;
}

export function angleStats(angles: Float64Array): AngleStats {
  let min = Infinity, max = -Infinity, below20 = 0, below30 = 0, sumMin = 0;
  for (let i = 0; i < angles.length; ++i) {
    const a = angles[i]!;
    if (a < min) min = a;
    if (a > max) max = a;
    if (a < 20) ++below20;
    if (a < 30) ++below30;
  }
  for (let f = 0; f < angles.length; f += 3) sumMin += Math.min(angles[f]!, angles[f + 1]!, angles[f + 2]!);
  const n = Math.max(1, angles.length);
  return { min, max, meanMin: sumMin / Math.max(1, angles.length / 3), below20: below20 / n, below30: below30 / n };
}

/** Unit face normals (3·nF). */
export function faceNormals(mesh: MeshLike): Float64Array {
  const p = mesh.positions, t = mesh.triangles;
  const n = new Float64Array(t.length);
  for (let f = 0; f < t.length; f += 3) {
    const a = 3 * t[f]!, b = 3 * t[f + 1]!, c = 3 * t[f + 2]!;
    const ux = p[b]! - p[a]!, uy = p[b + 1]! - p[a + 1]!, uz = p[b + 2]! - p[a + 2]!;
    const vx = p[c]! - p[a]!, vy = p[c + 1]! - p[a + 1]!, vz = p[c + 2]! - p[a + 2]!;
    const x = uy * vz - uz * vy, y = uz * vx - ux * vz, z = ux * vy - uy * vx;
    const l = Math.hypot(x, y, z) || 1;
    n[f] = x / l; n[f + 1] = y / l; n[f + 2] = z / l;
  }
  return n;
}

export interface FeaturePreview {
  /** Vertex pairs of feature edges (sharp, boundary or non-manifold): 2·nE indices. */
  featureEdges: Uint32Array;
  /** Region id of every triangle: faces connected without crossing a feature edge. */
  patchOfFace: Uint32Array;
  patchCount: number;
}

/**
 * Feature edges (dihedral angle above `featureAngle` degrees, boundary and non-manifold edges)
 * and the regions they bound. This is only the first step of the library's segmentation (which
 * then cuts regions into disks); it is a live preview for the feature-angle slider.
 */
export function featurePreview(mesh: MeshLike, featureAngle: number): FeaturePreview {
  const t = mesh.triangles;
  const nF = t.length / 3;
  const nV = mesh.positions.length / 3;
  const nH = 3 * nF;
  const normals = faceNormals(mesh);
  const cosLimit = Math.cos((featureAngle * Math.PI) / 180);
  // half-edges h = 3f + k run from t[h] to t[next(h)]; bucket them by their start vertex (CSR)
  const next = (h: number) => (h % 3 === 2 ? h - 2 : h + 1);
  const start = new Uint32Array(nV + 1);
  for (let h = 0; h < nH; ++h) start[t[h]! + 1]!++;
  for (let v = 0; v < nV; ++v) start[v + 1]! += start[v]!;
  const fill = start.slice(0, nV);
  const out = new Uint32Array(nH);
  for (let h = 0; h < nH; ++h) out[fill[t[h]!]!++] = h;

  const parent = new Uint32Array(nF);
  for (let f = 0; f < nF; ++f) parent[f] = f;
  const find = (x: number): number => {
    while (parent[x] !== x) {
      parent[x] = parent[parent[x]!]!;
      x = parent[x]!;
    }
    return x;
  };
  const feature: number[] = [];
  const around: number[] = [];
  for (let h = 0; h < nH; ++h) {
    const a = t[h]!, b = t[next(h)]!;
    // every half-edge on the undirected edge {a, b}; handle the edge at its smallest half-edge
    around.length = 0;
    let first = true;
    for (let i = start[a]!; i < start[a + 1]! && first; ++i) {
      const g = out[i]!;
      if (t[next(g)] === b) {
        if (g < h) first = false;
        around.push(g);
      }
    }
    for (let i = start[b]!; i < start[b + 1]! && first; ++i) {
      const g = out[i]!;
      if (t[next(g)] === a) {
        if (g < h) first = false;
        around.push(g);
      }
    }
    if (!first) continue;
    let sharp = around.length !== 2;
    if (!sharp) {
      const f = Math.floor(around[0]! / 3), g = Math.floor(around[1]! / 3);
      const dot = normals[3 * f]! * normals[3 * g]! + normals[3 * f + 1]! * normals[3 * g + 1]! + normals[3 * f + 2]! * normals[3 * g + 2]!;
      sharp = dot < cosLimit;
      if (!sharp) {
        const rf = find(f), rg = find(g);
        if (rf !== rg) parent[rf] = rg;
      }
    }
    if (sharp) feature.push(a, b);
  }
  const patchOfFace = new Uint32Array(nF);
  const ids = new Int32Array(nF).fill(-1);
  let count = 0;
  for (let f = 0; f < nF; ++f) {
    const r = find(f);
    if (ids[r]! < 0) ids[r] = count++;
    patchOfFace[f] = ids[r]!;
  }
  return { featureEdges: Uint32Array.from(feature), patchOfFace, patchCount: count };
}
