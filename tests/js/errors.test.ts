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

  it('EmptyMesh: an empty file, and a file with vertices but no faces', async () => {
    expect((await codeOf(() => cm.readMesh('', 'obj'))).code).toBe('EmptyMesh');
    expect((await codeOf(() => cm.readMesh('v 0 0 0\nv 1 0 0\n', 'obj'))).code).toBe('EmptyMesh');
  });

  it('IndexOutOfRange: an OBJ face naming a missing vertex; a negative index in an array', async () => {
    expect((await codeOf(() => cm.readMesh('v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n', 'obj'))).code).toBe('IndexOutOfRange');
    const tri = [0, 0, 0, 1, 0, 0, 0, 1, 0];
    expect((await codeOf(() => cm.writeMesh({ positions: tri, triangles: [0, 1, -1] }, 'obj'))).code).toBe('IndexOutOfRange');
    expect((await codeOf(() => cm.writeMesh({ positions: tri, triangles: [0, 1, 3] }, 'obj'))).code).toBe('IndexOutOfRange');
  });

  it('NonFiniteCoordinate: a NaN in a binary STL, and in a positions array', async () => {
    expect((await codeOf(() => cm.readMesh(stlWithCoordinate(Number.NaN), 'stl'))).code).toBe('NonFiniteCoordinate');
    expect(
      (await codeOf(() => cm.writeMesh({ positions: [0, 0, 0, Infinity, 0, 0, 0, 1, 0], triangles: [0, 1, 2] }, 'off'))).code,
    ).toBe('NonFiniteCoordinate');
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
