// Determinism of remesh (issue 8): run to run bit-identical in WASM, and native (g++, glibc) and
// WASM (clang, emscripten's musl) byte-identical. Both builds compile the library with
// -ffp-contract=off and EIGEN_DONT_VECTORIZE, and the pipeline calls conformesh::dmath
// (src/core/detmath.h) instead of the platform libm, whose last bits differ between glibc and musl
// (docs/ARCHITECTURE.md, "Determinism"). The last test keeps new libm calls out of src/.
import { spawnSync } from 'node:child_process';
import { mkdirSync, readdirSync, readFileSync, statSync, writeFileSync } from 'node:fs';
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

    it(`${name}: native and WASM outputs are byte-identical`, async () => {
      const r = await both(name, bytes(), args, options);
      expect(r.wasm.equals(r.native)).toBe(true);
    });
  }

  it('the report\'s Hausdorff distance is the same number natively and in WASM', async () => {
    const cm = await init();
    const bytes = dataFile('fandisk.off');
    mkdirSync(tmp, { recursive: true });
    const input = join(tmp, 'fandisk-hausdorff.off');
    writeFileSync(input, bytes);
    const nat = spawnSync(native, ['remesh', input, '--edge-length-rel', '0.03', '--json'], { encoding: 'utf8' });
    expect(nat.status).toBe(0);
    const w = cm.remesh(cm.readMesh(bytes, { fileName: 'fandisk.off' }), { targetEdgeLengthRel: 0.03 });
    const n = JSON.parse(nat.stdout);
    expect(n.hausdorffRel).toBeGreaterThan(0);
    expect(w.report.hausdorffRel).toBe(n.hausdorffRel);
  });

  it('src/ calls no libm transcendental or std::complex function outside src/cli/ (conformesh::dmath instead)', () => {
    const libm = /\bstd::(exp|exp2|expm1|log|log2|log10|log1p|pow|cbrt|sin|cos|tan|asin|acos|atan|atan2|sinh|cosh|tanh|hypot|erf|erfc|tgamma|lgamma|norm|arg|polar)\s*\(/;
    const offenders: string[] = [];
    const walk = (dir: string) => {
      for (const e of readdirSync(dir)) {
        const p = join(dir, e);
        if (statSync(p).isDirectory()) {
          if (e !== 'cli') walk(p);
        } else if (/\.(h|cpp)$/.test(e) && !/detmath/.test(e)) {
          readFileSync(p, 'utf8').split('\n').forEach((line, i) => {
            if (libm.test(line.replace(/\/\/.*$/, ''))) offenders.push(`${p}:${i + 1}: ${line.trim()}`);
          });
        }
      }
    };
    walk(join(root, 'src'));
    expect(offenders).toEqual([]);
  });
});
