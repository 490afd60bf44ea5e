// flatten: convergence and Gauss–Bonnet fields of the report, the layout checked in JS (signed
// areas), one uv per vertex, circle boundary, errors, worker vs direct.
import { afterAll, describe, expect, it } from 'vitest';
import { createRemesher, flatten, init, readMesh, type ProgressEvent } from '../../dist/index.js';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { dataFile, root } from './helpers.js';

const sample = (name: string) => readFileSync(join(root, 'web', 'samples', name));

/** Signed area of each triangle of a planar layout (x, y taken from stride-`dim` positions). */
function signedAreas(p: Float64Array, t: Uint32Array, dim: number): Float64Array {
  const out = new Float64Array(t.length / 3);
  for (let k = 0; k < out.length; ++k) {
    const a = dim * t[3 * k]!, b = dim * t[3 * k + 1]!, c = dim * t[3 * k + 2]!;
    out[k] = 0.5 * ((p[b]! - p[a]!) * (p[c + 1]! - p[a + 1]!) - (p[b + 1]! - p[a + 1]!) * (p[c]! - p[a]!));
  }
  return out;
}

describe('flatten', async () => {
  const alligator = await readMesh(dataFile('alligator.obj'));
  const nV = alligator.positions.length / 3;

  // circle boundary on face.obj (a face scan, disk). (alligator.obj with a circle boundary fails
  // with NumericalFailure in the library: its area distortion is too large for the layout.)
  it('face (disk), circle boundary: converged, Gauss–Bonnet holds, one uv per vertex, no inverted layout triangle, round boundary', async () => {
    const face = await readMesh(dataFile('face.obj'));
    const nV = face.positions.length / 3;
    const r = await flatten(face);
    expect(r.uv.length).toBe(2 * nV);
    expect(r.u.length).toBe(nV);
    expect(r.uv.every(Number.isFinite) && r.u.every(Number.isFinite)).toBe(true);
    expect(r.report.maxCurvatureError).toBeLessThanOrEqual(1e-9);
    expect(r.report.residuals.at(-1)!).toBeLessThanOrEqual(1e-9);
    expect(r.report.residuals.length).toBe(r.report.iterations + 1);
    expect(r.report.residuals[0]!).toBeGreaterThan(r.report.residuals.at(-1)!);
    expect(r.report.iterations).toBeGreaterThan(0);
    expect(r.report.iterations).toBeLessThanOrEqual(100);
    expect(r.report.gaussBonnetError).toBeLessThan(1e-8);
    expect(r.report.invertedTriangles).toBe(0);
    expect(r.report.boundaryCrossings).toBe(0);
    expect(r.report.boundaryLoops).toBe(1);
    // the intrinsic layout: every triangle positively oriented, computed here
    expect(r.layout.positions.length % 3).toBe(0);
    const areas = signedAreas(r.layout.positions, r.layout.triangles, 3);
    expect(areas.length).toBeGreaterThan(0);
    expect(Math.min(...areas)).toBeGreaterThan(0);
    expect(r.layout.positions.filter((_, i) => i % 3 === 2).every((z) => z === 0)).toBe(true);
    // the input triangles in uv: the count of inverted ones is what the report says
    const uvAreas = signedAreas(r.uv, face.triangles, 2);
    expect(uvAreas.filter((a) => a <= 0).length).toBe(r.report.inputTrianglesInvertedInUv);
    // circle boundary: the boundary vertices lie on one circle (least-squares fit
    // x² + y² = 2ax + 2by + c, then the spread of the distances to (a, b))
    expect(r.boundaryLoops.length).toBe(1);
    const loop = r.boundaryLoops[0]!;
    const M = [0, 0, 0, 0, 0, 0, 0, 0, 0], rhs = [0, 0, 0];
    for (const v of loop) {
      const x = r.uv[2 * v]!, y = r.uv[2 * v + 1]!, row = [2 * x, 2 * y, 1], q = x * x + y * y;
      for (let i = 0; i < 3; ++i) {
        rhs[i]! += row[i]! * q;
        for (let j = 0; j < 3; ++j) M[3 * i + j]! += row[i]! * row[j]!;
      }
    }
    const det = (m: number[]) =>
      m[0]! * (m[4]! * m[8]! - m[5]! * m[7]!) - m[1]! * (m[3]! * m[8]! - m[5]! * m[6]!) + m[2]! * (m[3]! * m[7]! - m[4]! * m[6]!);
    const col = (k: number) => M.map((x, i) => (i % 3 === k ? rhs[Math.floor(i / 3)]! : x));
    const cx = det(col(0)) / det(M), cy = det(col(1)) / det(M);
    const radii = Array.from(loop, (v) => Math.hypot(r.uv[2 * v]! - cx, r.uv[2 * v + 1]! - cy));
    expect((Math.max(...radii) - Math.min(...radii)) / Math.max(...radii)).toBeLessThan(1e-3);
  });

  it('free and corners boundaries converge with a valid layout', async () => {
    for (const boundary of ['free', 'corners'] as const) {
      const r = await flatten(alligator, { boundary });
      expect(r.report.maxCurvatureError).toBeLessThanOrEqual(1e-9);
      expect(Math.min(...signedAreas(r.layout.positions, r.layout.triangles, 3))).toBeGreaterThan(0);
    }
  });

  it('annulus (disk with a hole): two boundary loops, a valid layout; heap flat over 100 calls (and 100 failing ones)', async () => {
    const cm = await init();
    const annulus = cm.readMesh(sample('annulus.ply'));
    const r = cm.flatten(annulus);
    expect(r.report.boundaryLoops).toBe(2);
    expect(r.boundaryLoops.length).toBe(2);
    expect(r.report.gaussBonnetError).toBeLessThan(1e-8);
    expect(Math.min(...signedAreas(r.layout.positions, r.layout.triangles, 3))).toBeGreaterThan(0);
    const disk = cm.readMesh(sample('disk.obj'));
    const closed = cm.readMesh(sample('icosphere.obj'));
    cm.flatten(disk);
    const before = cm.heapStats().used;
    for (let i = 0; i < 100; ++i) {
      cm.flatten(disk, { boundary: i % 2 ? 'free' : 'circle' });
      expect(() => cm.flatten(closed)).toThrow(expect.objectContaining({ code: 'InvalidTopology' }));
    }
    expect(Math.abs(cm.heapStats().used - before)).toBeLessThanOrEqual(0.01 * before);
  });

  it('fails with InvalidTopology on a closed mesh, InvalidArgument on bad options, IterationLimit at the cap', async () => {
    const spot = await readMesh(dataFile('spot.obj'));
    await expect(flatten(spot)).rejects.toMatchObject({ code: 'InvalidTopology', stage: 'flatten' });
    await expect(flatten(alligator, { boundary: 'square' as never })).rejects.toMatchObject({ code: 'InvalidArgument' });
    await expect(flatten(alligator, { tolerance: -1 })).rejects.toMatchObject({ code: 'InvalidArgument' });
    await expect(flatten(alligator, { maxIterations: 1, tolerance: 1e-14 })).rejects.toMatchObject({
      code: 'IterationLimit',
    });
    await expect(flatten({ positions: [0, 0, 0], triangles: [0, 1, 2] })).rejects.toMatchObject({ code: 'IndexOutOfRange' });
  });
});

describe('flatten in workers', () => {
  const remesher = createRemesher({ workers: 1 });
  afterAll(() => remesher.terminate());

  it('gives the same result as a direct call, with progress ending at 1', async () => {
    const cm = await init();
    const mesh = cm.readMesh(dataFile('alligator.obj'));
    const events: ProgressEvent[] = [];
    const w = await remesher.flatten(mesh, { boundary: 'free' }, { onProgress: (e) => events.push(e) });
    const d = cm.flatten(mesh, { boundary: 'free' });
    expect(w.uv).toEqual(d.uv);
    expect(w.u).toEqual(d.u);
    expect(w.layout.triangles).toEqual(d.layout.triangles);
    expect(w.report.iterations).toBe(d.report.iterations);
    expect(events.at(-1)).toEqual({ stage: 'flatten', fraction: 1 });
    expect(events.every((e, i) => i === 0 || e.fraction >= events[i - 1]!.fraction)).toBe(true);
  });
});
