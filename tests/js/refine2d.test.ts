// refine2d and readPoly: properties of the output computed here in JS from the returned arrays
// (angles, input points first and unchanged, constrained edges on their segments), errors,
// progress and cancel, worker vs direct.
import { afterAll, describe, expect, it } from 'vitest';
import { ConformeshError, createRemesher, init, readPoly, refine2d, type ProgressEvent, type Refine2dResult } from '../../dist/index.js';
import { dataFile } from './helpers.js';

function pslgFile(name: string): Uint8Array {
  return dataFile(`pslg/${name}`);
}

/** Smallest angle (degrees) of each triangle. */
function triangleMinAngles(v: Float64Array, t: Uint32Array): Float64Array {
  const out = new Float64Array(t.length / 3);
  for (let k = 0; k < out.length; ++k) {
    const p = [t[3 * k]!, t[3 * k + 1]!, t[3 * k + 2]!].map((i) => [v[2 * i]!, v[2 * i + 1]!] as const);
    let m = 180;
    for (let c = 0; c < 3; ++c) {
      const [ax, ay] = p[c]!;
      const [bx, by] = p[(c + 1) % 3]!;
      const [cx, cy] = p[(c + 2) % 3]!;
      const ux = bx - ax, uy = by - ay, wx = cx - ax, wy = cy - ay;
      m = Math.min(m, (Math.atan2(Math.abs(ux * wy - uy * wx), ux * wx + uy * wy) * 180) / Math.PI);
    }
    out[k] = m;
  }
  return out;
}

function signedAreas(v: Float64Array, t: Uint32Array): Float64Array {
  const out = new Float64Array(t.length / 3);
  for (let k = 0; k < out.length; ++k) {
    const a = t[3 * k]!, b = t[3 * k + 1]!, c = t[3 * k + 2]!;
    out[k] =
      0.5 * ((v[2 * b]! - v[2 * a]!) * (v[2 * c + 1]! - v[2 * a + 1]!) - (v[2 * b + 1]! - v[2 * a + 1]!) * (v[2 * c]! - v[2 * a]!));
  }
  return out;
}

/** A square with a square hole, as a PSLG. */
const squareWithHole = {
  points: new Float64Array([0, 0, 4, 0, 4, 4, 0, 4, 1.5, 1.5, 2.5, 1.5, 2.5, 2.5, 1.5, 2.5]),
  segments: new Uint32Array([0, 1, 1, 2, 2, 3, 3, 0, 4, 5, 5, 6, 6, 7, 7, 4]),
  holes: new Float64Array([2, 2]),
  segmentMarkers: new Int32Array([1, 1, 1, 1, 2, 2, 2, 2]),
};

describe('refine2d', () => {
  it('meets the angle bound on every non-exempt triangle, keeps the input points first and unchanged, respects area and holes', async () => {
    for (const minAngle of [20, 30, 33]) {
      const r = await refine2d(squareWithHole, { minAngle, maxArea: 0.05 });
      expect(r.status).toBe('Ok');
      const n = squareWithHole.points.length;
      expect(r.vertices.subarray(0, n)).toEqual(squareWithHole.points);
      const angles = triangleMinAngles(r.vertices, r.triangles);
      const below = angles.filter((a) => a < minAngle - 1e-9).length;
      expect(below).toBeLessThanOrEqual(r.exemptTriangles);
      expect(r.exemptTriangles).toBe(0); // the input angles are all 90°
      expect(Math.min(...angles)).toBeCloseTo(r.minAngle, 6);
      const areas = signedAreas(r.vertices, r.triangles);
      expect(Math.min(...areas)).toBeGreaterThan(0); // counter-clockwise, none degenerate
      expect(Math.max(...areas)).toBeLessThanOrEqual(0.05 * (1 + 1e-12));
      const total = areas.reduce((s, a) => s + a, 0);
      expect(total).toBeCloseTo(16 - 1, 9); // the hole is removed
      // per-vertex segment id and parameter reproduce the vertex
      for (let i = 0; i < r.vertexSegment.length; ++i) {
        const s = r.vertexSegment[i]!;
        if (s < 0) continue;
        const a = squareWithHole.segments[2 * s]!, b = squareWithHole.segments[2 * s + 1]!;
        const t = r.vertexParam[i]!;
        expect(t).toBeGreaterThanOrEqual(0);
        expect(t).toBeLessThanOrEqual(1);
        for (const c of [0, 1]) {
          const pa = squareWithHole.points[2 * a + c]!, pb = squareWithHole.points[2 * b + c]!;
          expect(Math.abs(r.vertices[2 * i + c]! - (pa + t * (pb - pa)))).toBeLessThan(1e-12);
        }
      }
      // constrained edges carry their segment's marker; their lengths add up to the segments'
      expect(r.edges.length / 2).toBe(r.edgeSegment.length);
      let constrained = 0;
      for (let e = 0; e < r.edgeSegment.length; ++e) {
        const s = r.edgeSegment[e]!;
        expect(r.edgeMarker[e]).toBe(squareWithHole.segmentMarkers[s]);
        const a = r.edges[2 * e]!, b = r.edges[2 * e + 1]!;
        constrained += Math.hypot(r.vertices[2 * a]! - r.vertices[2 * b]!, r.vertices[2 * a + 1]! - r.vertices[2 * b + 1]!);
      }
      expect(constrained).toBeCloseTo(16 + 4, 9);
    }
  });

  it('accepts plain arrays and meshes the convex hull of points without segments', async () => {
    const r = await refine2d({ points: [0, 0, 1, 0, 1, 1, 0, 1, 0.3, 0.6] }, { minAngle: 25 });
    const angles = triangleMinAngles(r.vertices, r.triangles);
    expect(Math.min(...angles)).toBeGreaterThanOrEqual(25 - 1e-9);
    expect(signedAreas(r.vertices, r.triangles).reduce((s, a) => s + a, 0)).toBeCloseTo(1, 12);
  });

  it('reports small input angles as exempt triangles, never as silent failures', async () => {
    // a thin wedge: 5° input angle at the origin
    const a = (5 * Math.PI) / 180;
    const r = await refine2d(
      { points: [0, 0, 10, 0, 10 * Math.cos(a), 10 * Math.sin(a)], segments: [0, 1, 1, 2, 2, 0] },
      { minAngle: 30 },
    );
    const angles = triangleMinAngles(r.vertices, r.triangles);
    expect(r.exemptTriangles).toBeGreaterThan(0);
    expect(angles.filter((x) => x < 30 - 1e-9).length).toBeLessThanOrEqual(r.exemptTriangles);
  });

  it('wiggly5000 (../shared/data/pslg) at 30°: every non-exempt triangle ≥ 30°', async () => {
    const cm = await init();
    const pslg = cm.readPoly(pslgFile('wiggly5000.poly'));
    expect(pslg.points.length % 2).toBe(0);
    const r = cm.refine2d(pslg, { minAngle: 30 });
    expect(r.status).toBe('Ok');
    expect(r.vertices.subarray(0, pslg.points.length)).toEqual(pslg.points);
    const angles = triangleMinAngles(r.vertices, r.triangles);
    expect(angles.filter((x) => x < 30 - 1e-9).length).toBeLessThanOrEqual(r.exemptTriangles);
    expect(Math.min(...signedAreas(r.vertices, r.triangles))).toBeGreaterThan(0);
  });

  it('stops at maxInsertions: throws IterationLimit with the valid mesh so far attached', async () => {
    const error = await refine2d(squareWithHole, { minAngle: 30, maxArea: 1e-4, maxInsertions: 50 }).catch((e: unknown) => e);
    expect(error).toBeInstanceOf(ConformeshError);
    expect(error).toMatchObject({ code: 'IterationLimit', stage: 'refine' });
    const r = (error as ConformeshError).result as Refine2dResult;
    expect(r.status).toBe('IterationLimit');
    expect(r.insertions).toBeLessThanOrEqual(50);
    expect(Math.min(...signedAreas(r.vertices, r.triangles))).toBeGreaterThan(0);
  });

  it('fails with InvalidPslg, IndexOutOfRange, NonFiniteCoordinate and InvalidArgument', async () => {
    const crossing = { points: [0, 0, 1, 1, 0, 1, 1, 0], segments: [0, 1, 2, 3] };
    await expect(refine2d(crossing)).rejects.toMatchObject({ code: 'InvalidPslg', stage: 'refine' });
    await expect(refine2d({ points: [0, 0, 1, 0, 2, 0] })).rejects.toMatchObject({ code: 'InvalidPslg' });
    await expect(refine2d({ points: [0, 0, 1, 0, 0, 1], segments: [0, 7] })).rejects.toMatchObject({
      code: 'IndexOutOfRange',
    });
    await expect(refine2d({ points: [0, 0, NaN, 0, 0, 1] })).rejects.toMatchObject({ code: 'NonFiniteCoordinate' });
    await expect(refine2d(squareWithHole, { minAngle: 40 })).rejects.toMatchObject({ code: 'InvalidArgument' });
    await expect(refine2d(squareWithHole, { maxArea: 1, maxEdge: 1 })).rejects.toMatchObject({ code: 'InvalidArgument' });
    await expect(refine2d({ points: [0, 0, 1] })).rejects.toMatchObject({ code: 'InvalidArgument' });
    await expect(refine2d(null as never)).rejects.toBeInstanceOf(ConformeshError);
    await expect(readPoly('1 2 0 0\n')).rejects.toMatchObject({ code: 'ParseError', stage: 'read' });
  });

  it('reports progress monotone in [0, 1], and cancels through the signal (direct call)', async () => {
    const cm = await init();
    const pslg = cm.readPoly(pslgFile('wiggly5000.poly'));
    const fractions: number[] = [];
    cm.refine2d(squareWithHole, { maxArea: 1e-3 }, { onProgress: (e) => fractions.push(e.fraction) });
    expect(fractions.length).toBeGreaterThan(0);
    expect(fractions.every((f, i) => f >= 0 && f <= 1 && (i === 0 || f >= fractions[i - 1]!))).toBe(true);
    const ac = new AbortController();
    let calls = 0;
    expect(() =>
      cm.refine2d(pslg, { minAngle: 30 }, { signal: ac.signal, onProgress: () => (++calls === 2 ? ac.abort() : undefined) }),
    ).toThrow(expect.objectContaining({ code: 'Cancelled' }));
    const before = cm.heapStats().used;
    for (let i = 0; i < 20; ++i) {
      try {
        cm.refine2d(squareWithHole, { maxArea: 0.01 }, { signal: AbortSignal.abort() });
      } catch {
        // already aborted: not started
      }
      try {
        cm.refine2d({ points: [0, 0, 1, 1, 0, 1, 1, 0], segments: [0, 1, 2, 3] });
      } catch {
        // InvalidPslg
      }
      cm.refine2d(squareWithHole, { maxArea: 0.01 });
    }
    expect(Math.abs(cm.heapStats().used - before)).toBeLessThanOrEqual(0.01 * before);
  });
});

describe('refine2d in workers', () => {
  const remesher = createRemesher({ workers: 1 });
  afterAll(() => remesher.terminate());

  it('gives the same result as a direct call, progress ending at 1', async () => {
    const cm = await init();
    const events: ProgressEvent[] = [];
    const viaWorker = await remesher.refine2d(squareWithHole, { minAngle: 32, maxArea: 0.02 }, { onProgress: (e) => events.push(e) });
    const direct = cm.refine2d(squareWithHole, { minAngle: 32, maxArea: 0.02 });
    for (const k of ['vertices', 'triangles', 'edges', 'edgeSegment', 'vertexSegment', 'vertexParam'] as const) {
      expect(viaWorker[k]).toEqual(direct[k]);
    }
    expect(viaWorker.minAngle).toBe(direct.minAngle);
    expect(events.at(-1)).toEqual({ stage: 'refine', fraction: 1 });
    expect(await remesher.readPoly(pslgFile('square_holes.poly'))).toEqual(cm.readPoly(pslgFile('square_holes.poly')));
  });

  it('the same error model as a direct call: IterationLimit thrown, the partial mesh attached', async () => {
    const cm = await init();
    const options = { minAngle: 30, maxArea: 1e-4, maxInsertions: 50 };
    const viaWorker = await remesher.refine2d(squareWithHole, options).catch((e: unknown) => e);
    let direct: unknown;
    try {
      cm.refine2d(squareWithHole, options);
    } catch (e) {
      direct = e;
    }
    for (const e of [viaWorker, direct]) {
      expect(e).toBeInstanceOf(ConformeshError);
      expect(e).toMatchObject({ code: 'IterationLimit', stage: 'refine' });
    }
    const w = (viaWorker as ConformeshError).result as Refine2dResult;
    const d = (direct as ConformeshError).result as Refine2dResult;
    expect(w.triangles).toEqual(d.triangles);
    expect(w.triangles.length).toBeGreaterThan(0);
  });

  it('cancels a running call through the signal (the worker is replaced)', async () => {
    const bytes = pslgFile('wiggly5000.poly');
    const pslg = await readPoly(bytes);
    const ac = new AbortController();
    const t0 = performance.now();
    const call = remesher.refine2d(pslg, { minAngle: 30, maxArea: 1e-9, maxInsertions: 5e6 }, {
      signal: ac.signal,
      onProgress: () => ac.abort(),
    });
    await expect(call).rejects.toMatchObject({ code: 'Cancelled' });
    expect(performance.now() - t0).toBeLessThan(30_000);
    // the pool still works
    const r = await remesher.refine2d(squareWithHole, { maxArea: 0.1 });
    expect(r.status).toBe('Ok');
  });
});
