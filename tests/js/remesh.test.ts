// remesh: the output's angles computed here in JS (3D) against the bound and the reported exempt
// corners, progress and cancel (direct and in workers), worker vs direct, heap flat.
import { afterAll, describe, expect, it } from 'vitest';
import { ConformeshError, createRemesher, init, remesh, type Mesh, type ProgressEvent } from '../../dist/index.js';
import { dataFile } from './helpers.js';

/** An axis-aligned cube [0,1]^3, each face an n×n grid of quads split in two, outward oriented. */
function cube(n: number): Mesh {
  const index = new Map<string, number>();
  const positions: number[] = [];
  const triangles: number[] = [];
  const vertex = (p: number[]) => {
    const key = p.map((x) => Math.round(x * n)).join(',');
    let i = index.get(key);
    if (i === undefined) {
      i = positions.length / 3;
      index.set(key, i);
      positions.push(...p);
    }
    return i;
  };
  // each face: origin o, axes a, b with a × b the outward normal
  const faces: [number[], number[], number[]][] = [
    [[0, 0, 0], [0, 1, 0], [1, 0, 0]], // z = 0, normal -z
    [[0, 0, 1], [1, 0, 0], [0, 1, 0]], // z = 1, normal +z
    [[0, 0, 0], [1, 0, 0], [0, 0, 1]], // y = 0, normal -y
    [[0, 1, 0], [0, 0, 1], [1, 0, 0]], // y = 1, normal +y
    [[0, 0, 0], [0, 0, 1], [0, 1, 0]], // x = 0, normal -x
    [[1, 0, 0], [0, 1, 0], [0, 0, 1]], // x = 1, normal +x
  ];
  for (const [o, a, b] of faces) {
    const at = (i: number, j: number) => vertex([0, 1, 2].map((c) => o[c]! + (a[c]! * i) / n + (b[c]! * j) / n));
    for (let i = 0; i < n; ++i) {
      for (let j = 0; j < n; ++j) {
        const p00 = at(i, j), p10 = at(i + 1, j), p11 = at(i + 1, j + 1), p01 = at(i, j + 1);
        triangles.push(p00, p10, p11, p00, p11, p01);
      }
    }
  }
  return { positions: new Float64Array(positions), triangles: new Uint32Array(triangles) };
}

/** Smallest angle (degrees) of each triangle, in 3D. */
function minAngles(p: Float64Array, t: Uint32Array): Float64Array {
  const out = new Float64Array(t.length / 3);
  for (let k = 0; k < out.length; ++k) {
    let m = 180;
    for (let c = 0; c < 3; ++c) {
      const a = 3 * t[3 * k + c]!, b = 3 * t[3 * k + ((c + 1) % 3)]!, d = 3 * t[3 * k + ((c + 2) % 3)]!;
      const u = [0, 1, 2].map((i) => p[b + i]! - p[a + i]!);
      const w = [0, 1, 2].map((i) => p[d + i]! - p[a + i]!);
      const dot = u[0]! * w[0]! + u[1]! * w[1]! + u[2]! * w[2]!;
      const cx = u[1]! * w[2]! - u[2]! * w[1]!, cy = u[2]! * w[0]! - u[0]! * w[2]!, cz = u[0]! * w[1]! - u[1]! * w[0]!;
      m = Math.min(m, (Math.atan2(Math.hypot(cx, cy, cz), dot) * 180) / Math.PI);
    }
    out[k] = m;
  }
  return out;
}

const small = cube(2);
const fast = { targetEdgeLengthRel: 0.15, computeHausdorff: false };

describe('remesh', () => {
  it('cube: every triangle ≥ the bound except at reported exempt corners, closed and oriented, on the surface', async () => {
    const input = cube(4);
    for (const minAngle of [25, 30]) {
      const r = await remesh(input, { minAngle, targetEdgeLengthRel: 0.05, hausdorffSamples: 2000 });
      const exempt = new Set<number>();
      for (const c of r.report.exemptCorners) for (const t of c.triangles) exempt.add(t);
      const angles = minAngles(r.mesh.positions, r.mesh.triangles);
      const bad = [...angles.keys()].filter((t) => angles[t]! < minAngle - 1e-9 && !exempt.has(t));
      expect(bad).toEqual([]);
      expect(r.report.triangles).toBe(r.mesh.triangles.length / 3);
      expect(r.report.vertices).toBe(r.mesh.positions.length / 3);
      expect(r.report.topologyPreserved).toBe(true);
      // closed and consistently oriented: each directed edge once, its reverse present
      const directed = new Set<string>();
      const t = r.mesh.triangles;
      for (let k = 0; k < t.length; k += 3) {
        for (let c = 0; c < 3; ++c) {
          const key = `${t[k + c]},${t[k + ((c + 1) % 3)]}`;
          expect(directed.has(key)).toBe(false);
          directed.add(key);
        }
      }
      for (const key of directed) expect(directed.has(key.split(',').reverse().join(','))).toBe(true);
      // every vertex on the cube's surface
      const p = r.mesh.positions;
      for (let v = 0; v < p.length; v += 3) {
        const x = [p[v]!, p[v + 1]!, p[v + 2]!];
        expect(Math.min(...x.map((c) => Math.min(Math.abs(c), Math.abs(c - 1))))).toBeLessThan(1e-9);
        expect(x.every((c) => c > -1e-9 && c < 1 + 1e-9)).toBe(true);
      }
    }
  });

  it('innerCreases (the default): a crease ending inside a flat square stays inside its one patch, kept as output edges', async () => {
    const n = 20;
    const positions: number[] = [];
    const triangles: number[] = [];
    const at = (i: number, j: number) => i * (n + 1) + j;
    for (let i = 0; i <= n; ++i) for (let j = 0; j <= n; ++j) positions.push(i / n, j / n, 0);
    for (let i = 0; i < n; ++i) {
      for (let j = 0; j < n; ++j) triangles.push(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
    const featureEdges: number[] = [];
    for (let i = 6; i < 14; ++i) featureEdges.push(at(i, 10), at(i + 1, 10));
    const input = { positions: new Float64Array(positions), triangles: new Uint32Array(triangles) };
    const options = { targetEdgeLengthRel: 0.03, hausdorffSamples: 1000, featureEdges };
    const inner = await remesh(input, options);
    expect(inner.report.patches).toBe(1);
    expect(inner.report.featureCurvesKept).toBe(inner.report.featureCurves);
    expect(inner.report.featureCurves).toBe(5); // the square's four sides and the crease
    expect(inner.report.trianglesBelowBoundOutsideExempt).toBe(0);
    const continued = await remesh(input, { ...options, innerCreases: false });
    expect(continued.report.patches).toBeGreaterThan(1);
  });

  it('reports progress monotone in [0, 1], cancels quickly, and fails with InvalidArgument / EmptyMesh', async () => {
    const cm = await init();
    const fractions: number[] = [];
    cm.remesh(small, fast, { onProgress: (e) => fractions.push(e.fraction) });
    expect(fractions.length).toBeGreaterThan(2);
    expect(fractions.every((f, i) => f >= 0 && f <= 1 && (i === 0 || f >= fractions[i - 1]!))).toBe(true);
    expect(fractions.at(-1)).toBe(1);
    const ac = new AbortController();
    const t0 = performance.now();
    expect(() => cm.remesh(cube(6), { minAngle: 30 }, { signal: ac.signal, onProgress: () => ac.abort() })).toThrow(
      expect.objectContaining({ code: 'Cancelled' }),
    );
    expect(performance.now() - t0).toBeLessThan(10_000);
    expect(() => cm.remesh(small, { minAngle: 50 })).toThrow(expect.objectContaining({ code: 'InvalidArgument' }));
    expect(() => cm.remesh({ positions: [], triangles: [] })).toThrow(expect.objectContaining({ code: 'EmptyMesh' }));
  });

  it('a broken output is an error: InternalError (stage report) saying what differs; keepDefectiveOutput attaches it', async () => {
    const cm = await init();
    const good = cm.remesh(small, fast);
    let err: unknown;
    try {
      cm.remesh(small, { ...fast, forceTopologyDefect: true });
    } catch (e) {
      err = e;
    }
    expect(err).toBeInstanceOf(ConformeshError);
    const e = err as ConformeshError;
    expect([e.code, e.stage]).toEqual(['InternalError', 'report']);
    expect(e.message).toMatch(/^output topology differs from the input: .*1 non-manifold edge\b/);
    expect(e.result).toBeUndefined();
    try {
      cm.remesh(small, { ...fast, forceTopologyDefect: true, keepDefectiveOutput: true });
    } catch (x) {
      err = x;
    }
    const kept = err as ConformeshError;
    expect(kept).not.toBe(e);
    expect([kept.code, kept.message]).toEqual([e.code, e.message]);
    expect(kept.result!.report.topologyPreserved).toBe(false);
    // the good output and one flipped copy of its first triangle on a new vertex
    expect(kept.result!.mesh.triangles.length).toBe(good.mesh.triangles.length + 3);
    expect(kept.result!.mesh.positions.length).toBe(good.mesh.positions.length + 3);
    expect(cm.meshInfo(kept.result!.mesh).nonManifoldEdges).toBe(1);
    // asked for, but no defect: the same result as without the option
    const same = cm.remesh(small, { ...fast, keepDefectiveOutput: true });
    expect(same.mesh.positions).toEqual(good.mesh.positions);
    expect(same.mesh.triangles).toEqual(good.mesh.triangles);
  });

  it("maxError: the report's Hausdorff distance within the bound, a looser bound coarser; a negative maxErrorRel is InvalidArgument", async () => {
    const cm = await init();
    const spot = cm.readMesh(dataFile('spot.obj'));
    const tight = cm.remesh(spot, { maxErrorRel: 2e-3, attributes: false });
    const loose = cm.remesh(spot, { maxErrorRel: 8e-3, attributes: false });
    expect(tight.report.hausdorffRel).toBeLessThanOrEqual(2e-3);
    expect(loose.report.hausdorffRel).toBeLessThanOrEqual(8e-3);
    expect(loose.report.triangles).toBeLessThan(tight.report.triangles);
    expect(tight.report.trianglesBelowBoundOutsideExempt).toBe(0);
    expect(() => cm.remesh(small, { maxErrorRel: -1 })).toThrow(/maxErrorRel = -1 must be >= 0/);
  });

  it('keeps the heap flat (±1 %) over 100 calls', async () => {
    const cm = await init();
    cm.remesh(small, fast);
    const before = cm.heapStats().used;
    for (let i = 0; i < 100; ++i) cm.remesh(small, fast);
    expect(Math.abs(cm.heapStats().used - before)).toBeLessThanOrEqual(0.01 * before);
  });
});

describe('remesh in workers', () => {
  const remesher = createRemesher({ workers: 1 });
  afterAll(() => remesher.terminate());

  it('gives the same mesh as a direct call, progress monotone ending at 1', async () => {
    const cm = await init();
    const events: ProgressEvent[] = [];
    const w = await remesher.remesh(small, fast, { onProgress: (e) => events.push(e) });
    const d = cm.remesh(small, fast);
    expect(w.mesh.positions).toEqual(d.mesh.positions);
    expect(w.mesh.triangles).toEqual(d.mesh.triangles);
    expect(w.report.minAngle).toBe(d.report.minAngle);
    expect(events.length).toBeGreaterThan(2);
    expect(events.every((e, i) => e.fraction >= 0 && e.fraction <= 1 && (i === 0 || e.fraction >= events[i - 1]!.fraction))).toBe(true);
    expect(events.at(-1)!.fraction).toBe(1);
  });

  it('patches: every patch in the plane, through the worker, consistent with the output mesh', async () => {
    const r = await remesher.remesh(cube(4), { ...fast, targetEdgeLengthRel: 0.1, patches: true });
    expect(r.patches?.length).toBe(r.report.patches);
    const pot = r.patchOfTriangle!;
    expect(pot.length).toBe(r.mesh.triangles.length / 3);
    const next = new Array<number>(r.patches!.length).fill(0);
    for (let t = 0; t < pot.length; ++t) {
      const p = r.patches![pot[t]!]!;
      const k = next[pot[t]!]++;
      for (let c = 0; c < 3; ++c) expect(p.refined.outputVertex[p.refined.triangles[3 * k + c]!]).toBe(r.mesh.triangles[3 * t + c]);
    }
    for (const p of r.patches!) {
      expect(p.layout.uv).toBeInstanceOf(Float64Array);
      expect(p.layout.uv.length).toBe(2 * p.layout.factor.length);
      expect(p.layout.triangles.length).toBe(3 * p.layout.inputFace.length);
    }
    // without the option, none
    expect((await remesher.remesh(small, fast)).patches).toBeUndefined();
  });

  it('boundary: each condition can be tried first; anything else is InvalidArgument', async () => {
    for (const boundary of ['free', 'corners', 'circle'] as const) {
      const r = await remesher.remesh(small, { ...fast, boundary });
      expect(r.report.topologyPreserved).toBe(true);
    }
    await expect(remesher.remesh(small, { ...fast, boundary: 'disk' as 'free' })).rejects.toMatchObject({ code: 'InvalidArgument' });
  });

  it('a broken output rejects with InternalError, the defective result attached when asked for', async () => {
    const call = remesher.remesh(small, { ...fast, forceTopologyDefect: true, keepDefectiveOutput: true });
    await expect(call).rejects.toMatchObject({ code: 'InternalError', stage: 'report' });
    const e = (await call.catch((x: unknown) => x)) as ConformeshError;
    expect(e).toBeInstanceOf(ConformeshError);
    expect(e.result!.mesh.triangles).toBeInstanceOf(Uint32Array);
    expect(e.result!.report.topologyPreserved).toBe(false);
    const plain = (await remesher.remesh(small, { ...fast, forceTopologyDefect: true }).catch((x: unknown) => x)) as ConformeshError;
    expect([plain.code, plain.result]).toEqual(['InternalError', undefined]);
  });

  it('cancel rejects with Cancelled at once', async () => {
    const ac = new AbortController();
    const t0 = performance.now();
    const call = remesher.remesh(cube(8), { minAngle: 30 }, { signal: ac.signal, onProgress: () => ac.abort() });
    await expect(call).rejects.toMatchObject({ code: 'Cancelled' });
    expect(performance.now() - t0).toBeLessThan(10_000);
    const again = await remesher.remesh(small, fast);
    expect(again.mesh.triangles.length).toBeGreaterThan(0);
  });
});
