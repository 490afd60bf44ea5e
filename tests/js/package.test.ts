// The packed package, installed into an empty folder, used from plain Node (no Vitest transforms).
import { execFileSync } from 'node:child_process';
import { existsSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { root } from './helpers.js';
import { packAndInstall } from './pack.js';

const spot = fileURLToPath(new URL('../../../shared/data/spot.obj', import.meta.url));

describe('npm package (tarball installed into an empty folder)', () => {
  let dir = '';
  beforeAll(() => {
    dir = packAndInstall('node');
  });
  afterAll(() => rmSync(dir, { recursive: true, force: true }));

  it('contains the ESM entry, the .d.ts, the .wasm, the worker and the CLI, and no sources', () => {
    const pkg = join(dir, 'node_modules', 'conformesh');
    for (const f of ['dist/index.js', 'dist/index.d.ts', 'dist/conformesh.wasm', 'dist/conformesh.mjs', 'dist/worker.js', 'dist/three.d.ts', 'dist/cli.js']) {
      expect(existsSync(join(pkg, f)), f).toBe(true);
    }
    expect(existsSync(join(pkg, 'src'))).toBe(false);
    expect(existsSync(join(pkg, 'bindings'))).toBe(false);
    const manifest = JSON.parse(readFileSync(join(pkg, 'package.json'), 'utf8'));
    expect(manifest.exports['./conformesh.wasm']).toBe('./dist/conformesh.wasm');
  });

  it('imports from Node, reads spot.obj, writes and re-reads it, in the main thread and in a worker', () => {
    const script = `
      import { readFile } from 'node:fs/promises';
      import { readMesh, writeMesh, createRemesher, ConformeshError } from 'conformesh';
      const bytes = await readFile(${JSON.stringify(spot)});
      const m = await readMesh(bytes);
      const back = await readMesh(await writeMesh(m, 'ply'));
      const same = back.positions.every((x, i) => x === m.positions[i]);
      const r = createRemesher();
      const w = await r.readMesh(bytes);
      r.terminate();
      let code = '';
      try { await readMesh('garbage'); } catch (e) { code = e instanceof ConformeshError ? e.code : 'not a ConformeshError'; }
      console.log(JSON.stringify({ nV: m.positions.length / 3, nF: m.triangles.length / 3, same, worker: w.triangles.length / 3, code }));
    `;
    writeFileSync(join(dir, 'use.mjs'), script);
    const out = JSON.parse(execFileSync(process.execPath, ['use.mjs'], { cwd: dir, encoding: 'utf8' }));
    expect(out).toEqual({ nV: 2930, nF: 5856, same: true, worker: 5856, code: 'ParseError' });
  });

  it('runs the package CLI: npx conformesh --help, remesh --help, --version', () => {
    const npx = (...args: string[]) => execFileSync('npx', ['--offline', 'conformesh', ...args], { cwd: dir, encoding: 'utf8' });
    expect(npx('--help')).toMatch(/conformesh info FILE/);
    expect(npx('remesh', '--help')).toMatch(/^ {2}--edge-length-rel R +target edge length/m);
    const { version } = JSON.parse(readFileSync(join(root, 'package.json'), 'utf8'));
    expect(npx('--version')).toBe(`conformesh ${version}\n`);
  });

  it('its type declarations compile in a strict consumer project', () => {
    writeFileSync(
      join(dir, 'consumer.ts'),
      `import { init, readMesh, ConformeshError, type Mesh, type ErrorCode, type MeshInfo } from 'conformesh';
       const cm = await init();
       const m: Mesh = await readMesh(new Uint8Array(0), { format: 'obj', weldTolerance: 0 });
       const bytes: Uint8Array = cm.writeMesh(m, 'stl');
       const code: ErrorCode = 'ParseError';
       let info: MeshInfo | undefined;
       try { info = cm.meshInfo(m); } catch (e) { if (e instanceof ConformeshError && e.code === code) console.log(e.stage, bytes.length); }
       export { info };
      `,
    );
    writeFileSync(
      join(dir, 'tsconfig.json'),
      JSON.stringify({
        compilerOptions: { strict: true, module: 'nodenext', target: 'es2022', lib: ['es2022', 'dom'], types: [], noEmit: true, skipLibCheck: false },
        files: ['consumer.ts'],
      }),
    );
    const tsc = join(root, 'node_modules', 'typescript', 'bin', 'tsc');
    execFileSync(process.execPath, [tsc, '-p', 'tsconfig.json'], { cwd: dir, encoding: 'utf8' });
  });
});
