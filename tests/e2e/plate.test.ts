import { describe, expect, it } from 'vitest';
import { meshInfo, readMesh } from '../../dist/index.js';
import { featurePreview } from '../../web/src/geometry.ts';
import { mountingPlate, mountingPlateOff } from '../../web/src/plate.ts';

// The generated CAD sample of the demo page must be a clean solid: the remesher's input contract.
describe('demo sample: mounting plate', () => {
  it('is closed, manifold, genus 5 (4 bolt holes + a slot) and outward oriented', () => {
    const plate = mountingPlate();
    const nV = plate.positions.length / 3;
    const nF = plate.triangles.length / 3;
    // every directed edge once, and its reverse present: closed, edge-manifold, consistently oriented
    const directed = new Set<number>();
    for (let f = 0; f < nF; ++f) {
      for (let k = 0; k < 3; ++k) {
        const a = plate.triangles[3 * f + k]!, b = plate.triangles[3 * f + ((k + 1) % 3)]!;
        const key = a * nV + b;
        expect(directed.has(key)).toBe(false);
        directed.add(key);
      }
    }
    for (const key of directed) expect(directed.has((key % nV) * nV + Math.floor(key / nV))).toBe(true);
    const used = new Set(plate.triangles);
    expect(used.size).toBe(nV);
    const euler = nV - directed.size / 2 + nF;
    expect((2 - euler) / 2).toBe(5);
    // signed volume (divergence theorem) ≈ the solid's volume: positive means outward normals
    const p = plate.positions, t = plate.triangles;
    let vol = 0;
    for (let f = 0; f < t.length; f += 3) {
      const a = 3 * t[f]!, b = 3 * t[f + 1]!, c = 3 * t[f + 2]!;
      vol += (p[a]! * (p[b + 1]! * p[c + 2]! - p[b + 2]! * p[c + 1]!) -
        p[a + 1]! * (p[b]! * p[c + 2]! - p[b + 2]! * p[c]!) +
        p[a + 2]! * (p[b]! * p[c + 1]! - p[b + 1]! * p[c]!)) / 6;
    }
    const box = 80 * 50 * 8;
    expect(vol).toBeGreaterThan(0.8 * box);
    expect(vol).toBeLessThan(box);
  });

  it('is what the library topology report says: closed, manifold, consistently oriented, genus 5', async () => {
    const info = await meshInfo(mountingPlate());
    expect(info).toMatchObject({ components: 1, boundaryLoops: 0, genus: 5, nonManifoldEdges: 0, nonManifoldVertices: 0, inconsistentFaces: 0, duplicateFaces: 0 });
  });

  it('page feature preview: only the 90° bottom rims are sharp at 40°, so the bottom face is its own patch', () => {
    const plate = mountingPlate();
    const p = featurePreview(plate, 40);
    expect(p.patchCount).toBe(2);
    for (let i = 0; i < p.featureEdges.length; ++i) expect(plate.positions[3 * p.featureEdges[i]! + 2]).toBe(0);
    // with a feature angle below one fillet step (90°/5 = 18°) every fillet ring is a feature too
    expect(featurePreview(plate, 10).patchCount).toBeGreaterThan(2 + 6 * 4);
  });

  it('round-trips through the library reader as OFF', async () => {
    const plate = mountingPlate();
    const read = await readMesh(mountingPlateOff(), 'off');
    expect(read.triangles.length).toBe(plate.triangles.length);
    expect(read.positions.length).toBe(plate.positions.length);
  });
});
