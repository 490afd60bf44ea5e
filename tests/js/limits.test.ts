// Output limits of remesh (maxTriangles / maxVertices / maxMemoryBytes): TooLarge reaches JS as a
// ConformeshError, before the heavy work; 0 is InvalidArgument; the package CLI has the flags.
import { spawnSync } from 'node:child_process';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { ConformeshError, init } from '../../dist/index.js';
import { root } from './helpers.js';

/** A unit square in z = 0, n × n quads split in two. */
function square(n: number) {
  const positions: number[] = [];
  const triangles: number[] = [];
  for (let j = 0; j <= n; ++j) for (let i = 0; i <= n; ++i) positions.push(i / n, j / n, 0);
  const id = (i: number, j: number) => j * (n + 1) + i;
  for (let j = 0; j < n; ++j)
    for (let i = 0; i < n; ++i) triangles.push(id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j), id(i + 1, j + 1), id(i, j + 1));
  return { positions: new Float64Array(positions), triangles: new Uint32Array(triangles) };
}

describe('remesh limits', () => {
  it('an output above maxTriangles throws ConformeshError TooLarge with the estimate and the limit, quickly', async () => {
    const cm = await init();
    const t0 = performance.now();
    let caught: unknown;
    try {
      // about 2 / (√3/4 · (1.4e-4)²) ≈ 2.3e8 triangles
      cm.remesh(square(4), { targetEdgeLengthRel: 1e-4, minEdgeLength: 1e-4, computeHausdorff: false });
    } catch (e) {
      caught = e;
    }
    expect(performance.now() - t0).toBeLessThan(5000);
    expect(caught).toBeInstanceOf(ConformeshError);
    const err = caught as ConformeshError;
    expect(err.code).toBe('TooLarge');
    expect(err.message).toMatch(/about \d+ triangles, above maxTriangles = 33554432/);
    expect(() => cm.remesh(square(4), { targetEdgeLengthRel: 0.1, maxTriangles: 10 })).toThrow(
      expect.objectContaining({ code: 'TooLarge' }),
    );
    expect(() => cm.remesh(square(4), { targetEdgeLengthRel: 0.1, maxMemoryBytes: 1000 })).toThrow(
      expect.objectContaining({ code: 'TooLarge' }),
    );
  });

  it('a generous limit passes; 0 is InvalidArgument, not unlimited', async () => {
    const cm = await init();
    const r = cm.remesh(square(4), { targetEdgeLengthRel: 0.1, computeHausdorff: false, maxTriangles: 100000, maxVertices: 100000 });
    expect(r.report.triangles).toBeGreaterThan(0);
    expect(r.report.estimatedTriangles).toBeGreaterThan(0.5 * r.report.triangles);
    expect(r.report.estimatedTriangles).toBeLessThan(2 * r.report.triangles);
    // a huge limit is no limit (saturates to the largest size_t of the 32-bit module)
    expect(cm.remesh(square(4), { targetEdgeLengthRel: 0.1, computeHausdorff: false, maxTriangles: 1e15 }).report.triangles).toBe(
      r.report.triangles,
    );
    for (const key of ['maxTriangles', 'maxVertices', 'maxMemoryBytes'])
      expect(() => cm.remesh(square(4), { [key]: 0 })).toThrow(expect.objectContaining({ code: 'InvalidArgument' }));
  });

  it('package CLI: --max-triangles gives the TooLarge error JSON (exit 1), as the native CLI', () => {
    const input = join(root, 'web', 'samples', 'icosphere.obj');
    const r = spawnSync(process.execPath, [join(root, 'dist', 'cli.js'), 'remesh', input, '--max-triangles', '50', '--json'], {
      encoding: 'utf8',
    });
    expect(r.status).toBe(1);
    expect(JSON.parse(r.stdout).error).toMatchObject({ name: 'TooLarge' });
  });
});
