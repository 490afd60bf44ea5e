import { describe, expect, it } from 'vitest';
import { ConformeshError, init, meshInfo, readMesh, validateMesh, writeMesh, type MeshFormat } from '../../dist/index.js';
import { dataFile } from './helpers.js';

const tetra = {
  positions: new Float64Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1]),
  triangles: new Uint32Array([0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2]),
};

describe('readMesh', () => {
  it('reads every test mesh format (OBJ, OFF, binary STL) into flat typed arrays with valid indices', async () => {
    for (const name of ['spot.obj', 'fandisk.off', 't13_data.stl']) {
      const m = await readMesh(dataFile(name), { fileName: name });
      expect(m.positions).toBeInstanceOf(Float64Array);
      expect(m.triangles).toBeInstanceOf(Uint32Array);
      expect(m.positions.length % 3).toBe(0);
      expect(m.triangles.length % 3).toBe(0);
      const nV = m.positions.length / 3;
      expect(nV).toBeGreaterThan(0);
      expect(m.triangles.every((i) => i < nV)).toBe(true);
      expect(m.positions.every(Number.isFinite)).toBe(true);
      expect(Array.isArray(m.warnings)).toBe(true);
    }
  });

  it('accepts bytes as Uint8Array, ArrayBuffer, another view, or text, with the same result', async () => {
    const bytes = dataFile('spot.obj');
    const a = await readMesh(bytes);
    const copy = bytes.slice();
    const b = await readMesh(copy.buffer);
    const c = await readMesh(new DataView(copy.buffer));
    const d = await readMesh(new TextDecoder().decode(bytes));
    for (const x of [b, c, d]) {
      expect(x.positions).toEqual(a.positions);
      expect(x.triangles).toEqual(a.triangles);
    }
    expect(a.format).toBe('obj');
  });

  it('returns copies: results stay valid after the module heap grows', async () => {
    const cm = await init();
    const a = cm.readMesh(dataFile('spot.obj'));
    const first = a.positions.slice();
    cm.readMesh(dataFile('stanford-bunny.obj')); // a bigger mesh: the heap grows
    expect(a.positions.length).toBe(first.length);
    expect(a.positions).toEqual(first);
    expect(a.positions.buffer).not.toBe(new Float64Array(0).buffer);
  });
});

describe('writeMesh', () => {
  const formats: MeshFormat[] = ['obj', 'off', 'stl', 'stl-ascii', 'ply', 'ply-ascii'];
  it.each(formats)('round-trips spot.obj through %s (positions exact up to welding/format precision)', async (format) => {
    const m = await readMesh(dataFile('spot.obj'));
    const bytes = await writeMesh(m, format);
    expect(bytes).toBeInstanceOf(Uint8Array);
    const back = await readMesh(bytes, format);
    expect(back.triangles.length).toBe(m.triangles.length);
    if (format.startsWith('stl')) {
      // STL stores float32 triangle soups: compare every corner position at float precision.
      for (let t = 0; t < m.triangles.length; t += 997) {
        for (let k = 0; k < 3; ++k) {
          const p = m.triangles[t]! * 3 + k;
          const q = back.triangles[t]! * 3 + k;
          expect(back.positions[q]).toBeCloseTo(Math.fround(m.positions[p]!), 6);
        }
      }
    } else {
      expect(back.positions).toEqual(m.positions);
      expect(back.triangles).toEqual(m.triangles);
    }
  });

  it('accepts plain number arrays', async () => {
    const bytes = await writeMesh({ positions: Array.from(tetra.positions), triangles: Array.from(tetra.triangles) }, 'off');
    const back = await readMesh(bytes);
    expect(back.positions).toEqual(tetra.positions);
    expect(back.triangles).toEqual(tetra.triangles);
  });
});

describe('meshInfo', () => {
  it('reports vertices, faces, components, boundary loops, Euler characteristic and genus (spot: closed genus 0)', async () => {
    const cm = await init();
    const m = cm.readMesh(dataFile('spot.obj'));
    const info = await meshInfo(m);
    expect(info.vertices).toBe(m.positions.length / 3);
    expect(info.faces).toBe(m.triangles.length / 3);
    expect(info.components).toBe(1);
    expect(info.boundaryLoops).toBe(0);
    expect(info.euler).toBe(2);
    expect(info.genus).toBe(0);
  });

  it('a tetrahedron is a sphere, an open triangle a disk', async () => {
    const t = await meshInfo(tetra);
    expect([t.euler, t.genus, t.boundaryLoops]).toEqual([2, 0, 0]);
    const d = await meshInfo({ positions: [0, 0, 0, 1, 0, 0, 0, 1, 0], triangles: [0, 1, 2] });
    expect([d.euler, d.genus, d.boundaryLoops]).toEqual([1, 0, 1]);
  });

  it('counts instead of failing on a non-manifold edge (three triangles on one edge)', async () => {
    const info = await meshInfo({
      positions: [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1],
      triangles: [0, 1, 2, 1, 0, 3, 0, 1, 4],
    });
    expect(info.nonManifoldEdges).toBe(1);
    expect(info.warnings.length).toBeGreaterThan(0);
  });
});

describe('validateMesh', () => {
  it('returns a repaired mesh: a flipped face of a tetrahedron reoriented, a degenerate face dropped, with the report', async () => {
    const triangles = Uint32Array.from(tetra.triangles);
    [triangles[3], triangles[4]] = [triangles[4]!, triangles[3]!]; // flip face 1
    const withDegenerate = { positions: tetra.positions, triangles: Uint32Array.from([...triangles, 0, 1, 1]) };
    const { mesh, report, faceToInput, vertexToInput } = await validateMesh(withDegenerate);
    expect(mesh.triangles.length).toBe(12);
    expect(report.flippedFaces).toBe(1);
    expect(report.degenerateFaces).toBe(1);
    expect(report.warnings.map((w) => w.code).sort()).toEqual(['DegenerateFace', 'InconsistentOrientation']);
    expect(Array.from(faceToInput)).toEqual([0, 1, 2, 3]);
    expect(Array.from(vertexToInput)).toEqual([0, 1, 2, 3]);
    // Consistent orientation: every directed edge appears once.
    const directed = new Set<string>();
    for (let t = 0; t < 4; ++t) for (let k = 0; k < 3; ++k) directed.add(`${mesh.triangles[3 * t + k]}-${mesh.triangles[3 * t + ((k + 1) % 3)]}`);
    expect(directed.size).toBe(12);
    const info = await meshInfo(mesh);
    expect(info.inconsistentFaces).toBe(0);
  });

  it('keeps a valid mesh (spot) as it is', async () => {
    const m = await readMesh(dataFile('spot.obj'));
    const v = await validateMesh(m);
    expect(v.mesh.positions).toEqual(m.positions);
    expect(v.mesh.triangles).toEqual(m.triangles);
    expect(v.report.flippedFaces + v.report.degenerateFaces + v.report.removedVertices).toBe(0);
  });
});

describe('init', () => {
  it('returns the same instance every time and a version string', async () => {
    const a = await init();
    expect(await init()).toBe(a);
    expect(a.version).toMatch(/^\d+\.\d+\.\d+$/);
  });

  it('errors are ConformeshErrors, never raw module exceptions', async () => {
    await expect(readMesh(new Uint8Array(0))).rejects.toBeInstanceOf(ConformeshError);
  });
});
