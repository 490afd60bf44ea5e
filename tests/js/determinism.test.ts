// Determinism of remesh (issue 8). Run to run, in WASM: bit-identical. Native (g++, glibc libm) vs
// WASM (clang, emscripten's musl libm): NOT bit-identical today, and this file says exactly what
// holds. Both builds compile the library with -ffp-contract=off (no FMA contraction) and the
// planar stage alone is bit-identical (tests/js/cli.test.ts, refine2d). Two causes remain, both
// in the flattening: (1) libm: glibc and musl round exp/sin/cos/atan2/hypot/asin/acos differently
// in the last bit for a few % of arguments (atan2 18 %, asin 24 %, hypot 13 %, sin/cos 3 %,
// exp 0.07 % of 1e5 random arguments); (2) Eigen vectorizes dense reductions with SSE2 natively
// (another summation order) and not in WASM (no -msimd128): a native build with
// -DEIGEN_DONT_VECTORIZE flattens camelhead.off to other bits than the default native build.
// The Ricci flow and the layout carry those differences (relative 1e-14 in the flattened
// coordinates), and the planar refinement then makes some different decisions: the triangle
// counts differ by about 1 %. Identity needs one implementation of those functions compiled into
// both builds, and scalar Eigen natively (flatten about 10 % slower).
import { spawnSync } from 'node:child_process';
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { init } from '../../dist/index.js';
import { dataFile, root } from './helpers.js';

const native = join(root, 'build', 'native', 'conformesh');
const tmp = join(root, 'build', 'determinism');

/** The same remesh in WASM (this process) and with the native CLI: OFF bytes of both outputs. */
async function both(name: string, bytes: Uint8Array, args: string[], options: object) {
  const cm = await init();
  mkdirSync(tmp, { recursive: true });
  const input = join(tmp, name);
  writeFileSync(input, bytes);
  const out = join(tmp, `${name}.native.off`);
  const nat = spawnSync(native, ['remesh', input, '-o', out, '--no-hausdorff', '--json', ...args], { encoding: 'utf8' });
  expect(nat.status).toBe(0);
  const w = cm.remesh(cm.readMesh(bytes, { fileName: name }), { computeHausdorff: false, ...options });
  const w2 = cm.remesh(cm.readMesh(bytes, { fileName: name }), { computeHausdorff: false, ...options });
  return {
    wasm: Buffer.from(cm.writeMesh(w.mesh, 'off')),
    wasmAgain: Buffer.from(cm.writeMesh(w2.mesh, 'off')),
    native: readFileSync(out),
    wasmReport: w.report,
    nativeReport: JSON.parse(nat.stdout),
  };
}

const cases: [string, () => Uint8Array, string[], object][] = [
  ['fandisk.off', () => dataFile('fandisk.off'), ['--edge-length-rel', '0.03'], { targetEdgeLengthRel: 0.03 }],
  ['icosphere.obj', () => readFileSync(join(root, 'web', 'samples', 'icosphere.obj')), ['--edge-length-rel', '0.05'], { targetEdgeLengthRel: 0.05 }],
];

describe('remesh determinism', () => {
  for (const [name, bytes, args, options] of cases) {
    it(`${name}: WASM bit-identical run to run; native and WASM both succeed with triangle counts within 3 %`, async () => {
      const r = await both(name, bytes(), args, options);
      expect(r.wasmAgain.equals(r.wasm)).toBe(true);
      const n = r.nativeReport, w = r.wasmReport;
      expect(w.topologyPreserved).toBe(n.topologyPreserved);
      expect(w.patches).toBe(n.patches);
      expect(Math.abs(w.triangles - n.triangles)).toBeLessThanOrEqual(0.03 * n.triangles);
    });

    // Known failure (see the top of this file): flips to a plain `it` once both builds share one
    // implementation of the transcendental functions.
    it.fails(`${name}: native and WASM outputs are byte-identical`, async () => {
      const r = await both(name, bytes(), args, options);
      expect(r.wasm.equals(r.native)).toBe(true);
    });
  }
});
