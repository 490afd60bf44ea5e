// Shared by the Vitest suites: the built package (dist/) and the shared test meshes.
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

/** The project root (tests/js/../..). */
export const root = fileURLToPath(new URL('../../', import.meta.url));

/** A mesh file from ../shared/data (never copied into the repo). */
export function dataFile(name: string): Uint8Array {
  return readFileSync(new URL(`../../../shared/data/${name}`, import.meta.url));
}

/** A binary STL with one triangle whose first coordinate is `x` (e.g. NaN). */
export function stlWithCoordinate(x: number): Uint8Array {
  const buf = new ArrayBuffer(84 + 50);
  const view = new DataView(buf);
  view.setUint32(80, 1, true);
  const coords = [0, 0, 1, x, 0, 0, 1, 0, 0, 0, 1, 0];
  coords.forEach((c, i) => view.setFloat32(84 + 4 * i, c, true));
  return new Uint8Array(buf);
}
