import { BufferAttribute, BufferGeometry, InterleavedBuffer, InterleavedBufferAttribute, TorusGeometry } from 'three';
import { describe, expect, it } from 'vitest';
import { ConformeshError, init } from '../../dist/index.js';
import { fromBufferGeometry, toBufferGeometry } from '../../dist/three.js';
import { dataFile } from './helpers.js';

describe('conformesh/three', () => {
  it('toBufferGeometry: position/index/normal attributes matching the mesh; uvs when present', async () => {
    const m = (await init()).readMesh(dataFile('spot.obj'), { readUvs: false }); // its uv seams split vertices: attributes.test.ts
    const g = toBufferGeometry(m);
    expect(g.getAttribute('position').count).toBe(m.positions.length / 3);
    expect(Array.from(g.getIndex()!.array)).toEqual(Array.from(m.triangles));
    expect(g.getAttribute('normal').count).toBe(m.positions.length / 3);
    for (let i = 0; i < m.positions.length; i += 101) expect(g.getAttribute('position').array[i]).toBe(Math.fround(m.positions[i]!));
    const withUv = toBufferGeometry({ ...m, uvs: new Float64Array((2 * m.positions.length) / 3).fill(0.5) });
    expect(withUv.getAttribute('uv').count).toBe(m.positions.length / 3);
  });

  it('fromBufferGeometry ∘ toBufferGeometry keeps the triangles and float32 positions', async () => {
    const m = (await init()).readMesh(dataFile('fandisk.off'));
    const back = fromBufferGeometry(toBufferGeometry(m));
    expect(back.triangles).toEqual(m.triangles);
    expect(back.positions).toEqual(Float64Array.from(m.positions, Math.fround));
  });

  it('reads three.js geometries: indexed with uv, non-indexed, interleaved', () => {
    const torus = fromBufferGeometry(new TorusGeometry(1, 0.3, 8, 12));
    expect(torus.positions.length / 3).toBe(new TorusGeometry(1, 0.3, 8, 12).getAttribute('position').count);
    expect(torus.uvs?.length).toBe((2 * torus.positions.length) / 3);
    const soup = new BufferGeometry();
    soup.setAttribute('position', new BufferAttribute(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]), 3));
    expect(Array.from(fromBufferGeometry(soup).triangles)).toEqual([0, 1, 2]);
    const inter = new InterleavedBuffer(new Float32Array([0, 0, 0, 9, 1, 0, 0, 9, 0, 1, 0, 9]), 4);
    const ig = new BufferGeometry();
    ig.setAttribute('position', new InterleavedBufferAttribute(inter, 3, 0));
    expect(Array.from(fromBufferGeometry(ig).positions)).toEqual([0, 0, 0, 1, 0, 0, 0, 1, 0]);
  });

  it('bad input is a ConformeshError', () => {
    expect(() => fromBufferGeometry(new BufferGeometry())).toThrow(ConformeshError);
    expect(() => toBufferGeometry({ positions: [0, 0, 0], triangles: [0, 0, 1] })).toThrow(ConformeshError);
  });
});
