// The module survives abuse: many failing calls, and repeated I/O, leave its heap and stack as
// they were. Heap = bytes allocated by malloc inside the module (heapStats().used).
import { describe, expect, it } from 'vitest';
import { ConformeshError, init, type Conformesh } from '../../dist/index.js';
import { createRawInstance } from '../../dist/loader.js';
import { dataFile } from './helpers.js';

function expectConformeshError(f: () => unknown): void {
  try {
    f();
  } catch (e) {
    if (!(e instanceof ConformeshError)) throw e;
    return;
  }
  throw new Error('expected a ConformeshError');
}

describe('robustness', () => {
  it('100k invalid calls (C++ parse errors, library argument errors, facade type errors) do not break the module', async () => {
    const cm: Conformesh = await init();
    const raw = await createRawInstance(); // a second instance, to look at its stack pointer
    const spot = dataFile('spot.obj');
    cm.readMesh(spot); // warm up (heap reaches its working size)
    const usedBefore = cm.heapStats().used;
    const rawSpBefore = raw.stackSave();
    const bad = [
      () => cm.readMesh('v 0 0 0\nf 1 2 3\n'), // IndexOutOfRange thrown in C++
      () => cm.readMesh('solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n'), // ParseError
      () => cm.readMesh(new Uint8Array([1, 2, 3, 4])),
      () => cm.writeMesh({ positions: [0, 0, 0, 1, 0, 0, 0, 1, 0], triangles: [0, 1, 7] }, 'obj'),
      () => cm.writeMesh({ positions: [0, 0], triangles: [0, 1, 2] }, 'stl'),
      () => cm.writeMesh({ positions: [0, 0, 0], triangles: [0, 0, 0] }, 'nope' as never),
      () => cm.writeMesh(undefined as never, 'obj'),
      () => cm.readMesh(null as never),
    ];
    for (let i = 0; i < 100_000; ++i) expectConformeshError(bad[i % bad.length]!);
    // Raw glue calls straight into the module (no facade type checks): the result objects say ok: false.
    for (let i = 0; i < 1000; ++i) {
      const r = raw.readMesh!(new Uint8Array([0x4f, 0x46, 0x46]), 'off', '', 0, true, true);
      expect(r.ok).toBe(false);
    }
    expect(raw.stackSave()).toBe(rawSpBefore);
    expect(cm.heapStats().used).toBe(usedBefore);
    const m = cm.readMesh(spot);
    expect(m.triangles.length).toBe(3 * 5856);
  });

  it('heap flat (±1%) over 100 readMesh/writeMesh calls', async () => {
    const cm = await init();
    const spot = dataFile('spot.obj');
    const formats = ['obj', 'off', 'stl', 'ply'] as const;
    const round = (i: number) => {
      const m = cm.readMesh(spot);
      cm.readMesh(cm.writeMesh(m, formats[i % formats.length]!));
    };
    for (let i = 0; i < 4; ++i) round(i); // warm up
    const before = cm.heapStats();
    for (let i = 0; i < 100; ++i) round(i);
    const after = cm.heapStats();
    expect(Math.abs(after.used - before.used)).toBeLessThanOrEqual(0.01 * Math.max(before.used, 1));
    expect(after.heapSize).toBeLessThanOrEqual(before.heapSize * 1.01);
  });
});
