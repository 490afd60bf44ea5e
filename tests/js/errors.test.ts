// Every status code reachable from JS today, each from the call that produces it.
import { describe, expect, it } from 'vitest';
import { ConformeshError, createRemesher, init, type ErrorCode } from '../../dist/index.js';
import { dataFile, stlWithCoordinate } from './helpers.js';

async function codeOf(f: () => unknown): Promise<{ code: ErrorCode; stage: string; message: string }> {
  try {
    await f();
  } catch (e) {
    expect(e).toBeInstanceOf(ConformeshError);
    const err = e as ConformeshError;
    expect(err.message.length).toBeGreaterThan(5);
    return { code: err.code, stage: err.stage, message: err.message };
  }
  throw new Error('expected a ConformeshError');
}

describe('error codes reachable from JS', async () => {
  const cm = await init();

  it('ParseError: bytes that are no mesh file, with a line in the message', async () => {
    const e = await codeOf(() => cm.readMesh('v 0 0 0\nv 1 0 zero\nf 1 2 3\n', 'obj'));
    expect(e.code).toBe('ParseError');
    expect(e.stage).toBe('read');
    expect(e.message).toMatch(/line 2/);
  });

  it('EmptyMesh: an empty file, a file with vertices but no faces, a mesh of only degenerate triangles', async () => {
    expect((await codeOf(() => cm.validateMesh({ positions: [0, 0, 0, 1, 0, 0], triangles: [0, 1, 1] }))).code).toBe('EmptyMesh');
    expect((await codeOf(() => cm.readMesh('', 'obj'))).code).toBe('EmptyMesh');
    expect((await codeOf(() => cm.readMesh('v 0 0 0\nv 1 0 0\n', 'obj'))).code).toBe('EmptyMesh');
  });

  it('IndexOutOfRange: an OBJ face naming a missing vertex; a negative index in an array', async () => {
    expect((await codeOf(() => cm.readMesh('v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n', 'obj'))).code).toBe('IndexOutOfRange');
    const tri = [0, 0, 0, 1, 0, 0, 0, 1, 0];
    expect((await codeOf(() => cm.writeMesh({ positions: tri, triangles: [0, 1, -1] }, 'obj'))).code).toBe('IndexOutOfRange');
    expect((await codeOf(() => cm.writeMesh({ positions: tri, triangles: [0, 1, 3] }, 'obj'))).code).toBe('IndexOutOfRange');
    expect((await codeOf(() => cm.meshInfo({ positions: tri, triangles: [0, 1, 3] }))).code).toBe('IndexOutOfRange');
  });

  it('NonFiniteCoordinate: a NaN in a binary STL, and in a positions array', async () => {
    expect((await codeOf(() => cm.readMesh(stlWithCoordinate(Number.NaN), 'stl'))).code).toBe('NonFiniteCoordinate');
    const bad = { positions: [0, 0, 0, Infinity, 0, 0, 0, 1, 0], triangles: [0, 1, 2] };
    expect((await codeOf(() => cm.writeMesh(bad, 'off'))).code).toBe('NonFiniteCoordinate');
    expect((await codeOf(() => cm.meshInfo(bad))).code).toBe('NonFiniteCoordinate');
    expect((await codeOf(() => cm.validateMesh(bad))).code).toBe('NonFiniteCoordinate');
  });

  it('InvalidArgument: unknown format names, wrong types, array lengths not multiples of 3', async () => {
    const m = cm.readMesh(dataFile('spot.obj'));
    const cases: (() => unknown)[] = [
      () => cm.writeMesh(m, 'dxf' as never),
      () => cm.readMesh(dataFile('spot.obj'), 'dxf' as never),
      () => cm.readMesh(42 as never),
      () => cm.writeMesh(null as never, 'obj'),
      () => cm.writeMesh({ positions: 'abc', triangles: [] } as never, 'obj'),
      () => cm.writeMesh({ positions: m.positions.subarray(1), triangles: m.triangles }, 'obj'),
      () => cm.writeMesh({ positions: m.positions, triangles: m.triangles.subarray(1) }, 'obj'),
      () => cm.writeMesh({ ...m, uvs: new Float64Array(5) }, 'obj'),
      () => cm.writeMesh({ positions: [0, 0, 0, 1, 0, 0, 0, 1, 0], triangles: [0, 1, 1.5] }, 'obj'),
      () => cm.readMesh(dataFile('spot.obj'), { weldTolerance: -1 }),
      () => createRemesher({ workers: 0 }),
    ];
    for (const c of cases) expect((await codeOf(c)).code).toBe('InvalidArgument');
  });

  // A fan of three triangles around one edge; a bow-tie (two triangles sharing only vertex 0).
  const fin = { positions: [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1], triangles: [0, 1, 2, 1, 0, 3, 0, 1, 4] };
  const bowtie = { positions: [0, 0, 0, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0], triangles: [0, 1, 2, 0, 3, 4] };
  // A Möbius strip: four quads around a half twist (non-orientable).
  const mobius = (() => {
    const positions: number[] = [];
    const n = 4;
    for (let i = 0; i < n; ++i) {
      const a = (2 * Math.PI * i) / n;
      const t = a / 2;
      for (const s of [-0.3, 0.3]) {
        positions.push((1 + s * Math.cos(t)) * Math.cos(a), (1 + s * Math.cos(t)) * Math.sin(a), s * Math.sin(t));
      }
    }
    const triangles: number[] = [];
    for (let i = 0; i < n; ++i) {
      const a0 = 2 * i, a1 = 2 * i + 1;
      const last = i === n - 1;
      const b0 = last ? 1 : 2 * i + 2, b1 = last ? 0 : 2 * i + 3; // the twist swaps the sides
      triangles.push(a0, b0, a1, a1, b0, b1);
    }
    return { positions, triangles };
  })();

  it('NonManifoldEdge: an edge of three triangles (validateMesh); duplicate triangles', async () => {
    expect((await codeOf(() => cm.validateMesh(fin))).code).toBe('NonManifoldEdge');
    const dup = { positions: [0, 0, 0, 1, 0, 0, 0, 1, 0], triangles: [0, 1, 2, 0, 1, 2] };
    expect((await codeOf(() => cm.validateMesh(dup))).code).toBe('NonManifoldEdge');
    expect(cm.validateMesh(dup, { dropDuplicateFaces: true }).mesh.triangles.length).toBe(3);
  });

  it('NonManifoldVertex: a bow-tie, unless split', async () => {
    const e = await codeOf(() => cm.validateMesh(bowtie));
    expect(e.code).toBe('NonManifoldVertex');
    expect(e.stage).toBe('validate');
    const split = cm.validateMesh(bowtie, { splitNonManifoldVertices: true });
    expect(split.mesh.positions.length / 3).toBe(6);
  });

  it('InconsistentOrientation: a flipped triangle when repairs are off', async () => {
    const twoTriangles = { positions: [0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0], triangles: [0, 1, 2, 1, 2, 3] };
    expect((await codeOf(() => cm.validateMesh(twoTriangles, { fixOrientation: false }))).code).toBe('InconsistentOrientation');
  });

  it('InvalidTopology: a Möbius strip cannot be oriented', async () => {
    expect((await codeOf(() => cm.validateMesh(mobius))).code).toBe('InvalidTopology');
  });

  it('TooLarge: more triangles than the given limit', async () => {
    const m = cm.readMesh(dataFile('spot.obj'));
    expect((await codeOf(() => cm.meshInfo(m, { maxTriangles: 1000 }))).code).toBe('TooLarge');
    expect((await codeOf(() => cm.validateMesh(m, { maxVertices: 10 }))).code).toBe('TooLarge');
  });

  it('InvalidArgument: option values of the wrong type or range', async () => {
    const m = cm.readMesh(dataFile('spot.obj'));
    for (const o of [{ maxVertices: -1 }, { maxTriangles: Number.NaN }, { fixOrientation: 'yes' }, { dropZeroAreaFaces: {} }]) {
      expect((await codeOf(() => cm.validateMesh(m, o as never))).code).toBe('InvalidArgument');
    }
    // counts must be whole numbers (not silently truncated); the message names the option and
    // the allowed range in plain numbers
    const frac = await codeOf(() => cm.remesh(m, { optimizeIterations: 2.5 }));
    expect(frac.code).toBe('InvalidArgument');
    expect(frac.message).toMatch(/optimizeIterations = 2\.5 must be an integer/);
    const range = await codeOf(() => cm.remesh(m, { optimizeTolerance: -0.1 }));
    expect(range.message).toMatch(/optimizeTolerance = -0\.1 must be >= 0$/);
    expect((await codeOf(() => cm.remesh(m, { minAngle: 40 }))).message).toMatch(/minAngle = 40 must be in \[0, 35\]/);
  });

  it('Cancelled: an aborted worker call', async () => {
    const r = createRemesher();
    try {
      const ac = new AbortController();
      ac.abort();
      expect((await codeOf(() => r.readMesh(dataFile('spot.obj'), 'obj', { signal: ac.signal }))).code).toBe('Cancelled');
    } finally {
      r.terminate();
    }
  });
});
