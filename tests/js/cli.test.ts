// The package CLI (dist/cli.js, the `conformesh` bin) running the WASM module in Node: output,
// exit codes and JSON shapes; and, when the native CLI has the same command, identical output.
import { execFileSync, spawnSync } from 'node:child_process';
import { existsSync, readFileSync, rmSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it, vi } from 'vitest';
import { main } from '../../dist/cli.js';
import { init, REMESH_STAGES } from '../../dist/index.js';
import { dataFile, root } from './helpers.js';

const cli = join(root, 'dist', 'cli.js');
const native = join(root, 'build', 'native', 'conformesh');
const data = (name: string) => fileURLToPath(new URL(`../../../shared/data/${name}`, import.meta.url));

function run(args: string[]) {
  const r = spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8' });
  return { status: r.status, stdout: r.stdout, stderr: r.stderr };
}

const nativeHas = (command: string) =>
  existsSync(native) && execFileSync(native, ['--help'], { encoding: 'utf8' }).includes(`conformesh ${command} `);

describe('package CLI', () => {
  it('info FILE --json: the documented keys, equal to meshInfo() through the API', async () => {
    const cm = await init();
    for (const name of ['spot.obj', 'blade.off', 't13_data.stl']) {
      const r = run(['info', data(name), '--json']);
      expect(r.status).toBe(0);
      const json = JSON.parse(r.stdout);
      const info = cm.meshInfo(cm.readMesh(dataFile(name), { fileName: name }));
      expect(Object.keys(json)).toEqual([
        'vertices',
        'faces',
        'components',
        'boundaryLoops',
        'euler',
        'genus',
        'nonManifoldEdges',
        'degenerateFaces',
        'warnings',
      ]);
      for (const k of Object.keys(json).filter((k) => k !== 'warnings')) expect(json[k]).toBe(info[k as keyof typeof info]);
    }
  });

  it('info FILE: a readable report; errors: exit 1 with {"error":{code,name,stage,message}} under --json', () => {
    expect(run(['info', data('fertility.off')]).stdout).toMatch(/^genus +4$/m);
    const missing = run(['info', 'no-such-file.obj', '--json']);
    expect(missing.status).toBe(1);
    expect(JSON.parse(missing.stdout).error).toMatchObject({ code: 17, name: 'IoError', stage: 'read' });
    const bad = run(['info', data('spot.obj'), '--frobnicate']);
    expect(bad.status).toBe(1);
    expect(bad.stderr).toMatch(/unknown option --frobnicate/);
    expect(run(['frobnicate']).status).toBe(2);
    expect(run(['--help']).stdout).toMatch(/conformesh info FILE \[--json\]/);
  });

  it.skipIf(!nativeHas('info'))('info prints exactly what the native CLI prints: JSON, text, warnings, errors, exit codes', () => {
    const files = ['spot.obj', 't13_data.stl'].map(data);
    files.push(join(root, 'web', 'samples', 'needs-repair.obj')); // has warnings
    const cases = files.flatMap((f) => [['info', f, '--json'], ['info', f]]);
    cases.push(
      ['info', 'no-such-file.obj', '--json'],
      ['info', files[0]!, '--weld', 'x', '--json'],
      ['info', files[0]!, '--weld', '-1'],
      ['info', files[0]!, '--format', 'dxf', '--json'],
      ['info', files[0]!, '--format', 'OBJ', '--json'],
      ['info', '--json'],
    );
    for (const args of cases) {
      const wasm = run(args);
      const nat = spawnSync(native, args, { encoding: 'utf8' });
      expect({ args, out: wasm.stdout, err: wasm.stderr, status: wasm.status }).toEqual({
        args,
        out: nat.stdout,
        err: nat.stderr,
        status: nat.status,
      });
    }
  });
});

// --help on every command: the flags it prints are those its parser accepts. The candidates are
// every flag-like string of the CLI's source and every flag of the module's option table (remesh's
// flags come from it); the parser itself says which a command accepts.
describe('package CLI: --help and --version', () => {
  const commands = [...run(['--help']).stdout.matchAll(/^ {2}conformesh ([a-z0-9]+) /gm)].map((m) => m[1]!);
  const source = readFileSync(join(root, 'bindings', 'src', 'cli.ts'), 'utf8');
  const candidates = [...new Set([...source.matchAll(/'(--?[a-z][a-z0-9-]*)'/g)].map((m) => m[1]!))].filter(
    (f) => f !== '--help' && f !== '-h',
  );

  /** main() in this process, its output captured (fast: one module for every probe). */
  async function inProcess(args: string[]) {
    let out = '';
    const capture = (chunk: string | Uint8Array) => ((out += String(chunk)), true);
    const spies = [vi.spyOn(process.stdout, 'write').mockImplementation(capture), vi.spyOn(process.stderr, 'write').mockImplementation(capture)];
    try {
      return { status: await main(args), out };
    } finally {
      for (const spy of spies) spy.mockRestore();
    }
  }

  it('every command: --help and -h exit 0 with one text that lists exactly the flags its parser accepts', async () => {
    expect(commands).toEqual(expect.arrayContaining(['remesh', 'flatten', 'info', 'refine2d']));
    for (const command of commands) {
      const help = run([command, '--help']);
      expect(help.status, `${command} --help`).toBe(0);
      expect(help.stdout.startsWith(`usage: conformesh ${command} `)).toBe(true);
      expect(run([command, '-h']).stdout).toBe(help.stdout);
      expect((await inProcess([command, 'some-file', '--json', '--help'])).out).toBe(help.stdout);
      const listed = [...help.stdout.matchAll(/^ {2}(--?[a-z][a-z0-9-]*)/gm)].map((m) => m[1]!).filter((f) => f !== '-h');
      const accepted: string[] = [];
      const tableFlags = (await init()).remeshSchema().options.map((o) => o.flag).filter((f) => f !== '');
      for (const flag of new Set([...candidates, ...tableFlags])) {
        const r = await inProcess([command, flag]);
        if (!r.out.includes(`unknown option ${flag}`)) accepted.push(flag);
      }
      expect(accepted.length, command).toBeGreaterThan(0);
      expect([...listed].sort(), `${command}: flags in --help vs flags the parser accepts`).toEqual([...accepted].sort());
      const bad = await inProcess([command, '--frobnicate']);
      expect(bad.status).toBe(1);
      expect(bad.out).toMatch(/unknown option --frobnicate/);
    }
  });

  it.skipIf(!nativeHas('remesh'))('each --help is the native one, word for word: the same flags, units and defaults', () => {
    for (const command of commands) {
      const nat = spawnSync(native, [command, '--help'], { encoding: 'utf8' });
      expect({ command, help: run([command, '--help']).stdout }).toEqual({ command, help: nat.stdout });
    }
  });

  it('README.md shows `conformesh remesh --help` as the CLI prints it', () => {
    const readme = readFileSync(join(root, 'README.md'), 'utf8');
    const block = readme.match(/`conformesh remesh --help`:\n\n```text\n([\s\S]*?)```/)?.[1];
    expect(block).toBe(run(['remesh', '--help']).stdout);
  });

  it("--version prints package.json's version (as the native CLI does)", () => {
    const version = JSON.parse(readFileSync(join(root, 'package.json'), 'utf8')).version;
    const r = run(['--version']);
    expect(r.status).toBe(0);
    expect(r.stdout).toBe(`conformesh ${version}\n`);
    if (existsSync(native)) expect(execFileSync(native, ['--version'], { encoding: 'utf8' })).toBe(r.stdout);
  });
});

// refine2d / flatten / remesh: same JSON keys and exit codes as the native CLI (numbers that
// depend on timing differ; deterministic counts must agree).
describe('package CLI: refine2d, flatten, remesh', () => {
  const tmp = fileURLToPath(new URL('../../build/', import.meta.url));
  const poly = data('pslg/square_holes.poly');

  it('refine2d --json: the native keys, the mesh file written, errors as JSON', () => {
    const out = join(tmp, 'cli-refine2d.off');
    const r = run(['refine2d', poly, '--min-angle', '32', '--max-area', '0.05', '-o', out, '--json']);
    expect(r.status).toBe(0);
    const json = JSON.parse(r.stdout);
    expect(Object.keys(json)).toEqual([
      'triangles', 'vertices', 'minAngle', 'exemptTriangles', 'insertions', 'segmentSplits', 'rejected', 'seconds', 'status',
    ]);
    expect(json.minAngle).toBeGreaterThanOrEqual(32);
    expect(json.status).toBe('Ok');
    expect(existsSync(out)).toBe(true);
    const cap = run(['refine2d', poly, '--max-area', '1e-6', '--max-insertions', '10', '--json']);
    expect(cap.status).toBe(3);
    expect(JSON.parse(cap.stdout).status).toBe('IterationLimit');
    const bad = run(['refine2d', poly, '--max-area', '1', '--max-edge', '1', '--json']);
    expect(bad.status).toBe(1);
    expect(JSON.parse(bad.stdout).error).toMatchObject({ name: 'InvalidArgument' });
  });

  // Same bytes except timing, and except the last digits of minAngle (libm's atan2 differs
  // between the WASM and native builds): counts, status, exit code and errors are identical.
  it.skipIf(!nativeHas('refine2d'))('refine2d prints what the native CLI prints (seconds aside)', () => {
    const dir = join(tmp, 'cli-cmp');
    const cases = [
      ['refine2d', poly, '--min-angle', '30', '--json'],
      ['refine2d', poly, '--max-edge', '0.5', '--circumcenters', '--json'],
      ['refine2d', poly, '--max-area', '1e-6', '--max-insertions', '10', '--json'],
      ['refine2d', poly, '--min-angle', '50', '--json'],
      ['refine2d', 'no-such.poly', '--json'],
      ['refine2d', poly, '-o', join(dir, 'x.vtk'), '--json'],
    ];
    const strip = (s: string) => s.replace(/"seconds":[^,}]*/g, '"seconds":0').replace(/"minAngle":[^,}]*/g, '"minAngle":0');
    for (const args of cases) {
      const wasm = run(args);
      const nat = spawnSync(native, args, { encoding: 'utf8' });
      expect({ args, out: strip(wasm.stdout), status: wasm.status }).toEqual({ args, out: strip(nat.stdout), status: nat.status });
      const w = JSON.parse(wasm.stdout), n = JSON.parse(nat.stdout);
      if ('minAngle' in n) expect(Math.abs(w.minAngle - n.minAngle)).toBeLessThan(1e-9);
    }
    // the written meshes are identical
    const a = join(tmp, 'cli-wasm.obj'), b = join(tmp, 'cli-native.obj');
    run(['refine2d', poly, '--max-area', '0.1', '-o', a]);
    spawnSync(native, ['refine2d', poly, '--max-area', '0.1', '-o', b]);
    expect(readFileSync(a, 'utf8')).toBe(readFileSync(b, 'utf8'));
  });

  it.skipIf(!nativeHas('flatten'))('flatten --json: the native report and the same uv bytes', () => {
    const out = (who: string) => join(tmp, `cli-flat-${who}.obj`);
    const args = (who: string) => ['flatten', data('camelhead.off'), '-o', out(who), '--json'];
    const wasm = run(args('wasm'));
    expect(wasm.status).toBe(0);
    const nat = spawnSync(native, args('native'), { encoding: 'utf8' });
    const w = JSON.parse(wasm.stdout), n = JSON.parse(nat.stdout);
    expect(Object.keys(w)).toEqual(Object.keys(n));
    // the same bits in both builds (docs/ARCHITECTURE.md, "Determinism"): only the timing differs
    delete w.seconds;
    delete n.seconds;
    expect(w).toEqual(n);
    expect(readFileSync(out('wasm')).equals(readFileSync(out('native')))).toBe(true);
    const err = ['flatten', data('spot.obj'), '-o', join(tmp, 'x.obj'), '--json'];
    expect(run(err).stdout).toBe(spawnSync(native, err, { encoding: 'utf8' }).stdout);
  });

  // the OBJ's uv triangles of negative or zero signed area
  const invertedUvTriangles = (file: string) => {
    const vt: number[][] = [];
    let inverted = 0;
    for (const line of readFileSync(file, 'utf8').split('\n')) {
      const w = line.split(' ');
      if (w[0] === 'vt') vt.push([Number(w[1]), Number(w[2])]);
      if (w[0] !== 'f') continue;
      const [a, b, c] = w.slice(1).map((x) => vt[Number(x.split('/')[1]) - 1]!) as [number[], number[], number[]];
      inverted += (b[0]! - a[0]!) * (c[1]! - a[1]!) - (b[1]! - a[1]!) * (c[0]! - a[0]!) > 0 ? 0 : 1;
    }
    return inverted;
  };

  it('flatten: the report counts the inverted uv triangles of the file it writes (stanford-bunny, free boundary)', () => {
    const out = join(tmp, 'cli-flat-bunny.obj');
    const args = ['flatten', data('stanford-bunny.obj'), '--boundary', 'free', '-o', out];
    const json = run([...args, '--json']);
    expect(json.status).toBe(0);
    const report = JSON.parse(json.stdout);
    expect(report.invertedTriangles).toBe(0); // the intrinsic layout
    expect(report.inputTrianglesInvertedInUv).toBe(invertedUvTriangles(out));
    const text = run(args);
    expect(text.status).toBe(0);
    const warning = `conformesh: warning: ${report.inputTrianglesInvertedInUv} triangles of ${out} are inverted in uv`;
    expect(text.stderr.startsWith(warning)).toBe(report.inputTrianglesInvertedInUv > 0);
    if (nativeHas('flatten')) {
      for (const a of [[...args, '--json'], args]) {
        const nat = spawnSync(native, a, { encoding: 'utf8' });
        const wasm = run(a);
        const strip = (t: string) => t.replace(/"seconds":[^,}]*/g, '').replace(/, [0-9.]+ s ->/, '');
        expect({ out: strip(nat.stdout), err: nat.stderr, status: nat.status }).toEqual({ out: strip(wasm.stdout), err: wasm.stderr, status: wasm.status });
        expect(invertedUvTriangles(out)).toBe(report.inputTrianglesInvertedInUv);
      }
    }
  });

  it('remesh: a broken output exits 1 with the message, writes no file; --keep-defective writes it and still exits 1', () => {
    const input = join(root, 'web', 'samples', 'icosphere.obj');
    const out = join(tmp, 'cli-defect.obj');
    const args = ['remesh', input, '--edge-length-rel', '0.1', '--no-hausdorff', '--force-topology-defect', '-o', out];
    rmSync(out, { force: true });
    const broken = run(args);
    expect(broken.status).toBe(1);
    expect(broken.stderr).toMatch(/^conformesh: output topology differs from the input: .*1 non-manifold edge.* \(InternalError, stage report\)$/m);
    expect(broken.stdout).toBe('');
    expect(existsSync(out)).toBe(false);
    const kept = run([...args, '--keep-defective']);
    expect(kept.status).toBe(1);
    expect(kept.stderr).toBe(broken.stderr);
    expect(existsSync(out)).toBe(true);
    const json = run([...args, '--json']);
    expect(json.status).toBe(1);
    expect(JSON.parse(json.stdout).error).toMatchObject({ code: 18, name: 'InternalError', stage: 'report' });
    if (nativeHas('remesh')) {
      for (const a of [args, [...args, '--keep-defective'], [...args, '--json']]) {
        rmSync(out, { force: true });
        const nat = spawnSync(native, a, { encoding: 'utf8' });
        expect(existsSync(out)).toBe(a.includes('--keep-defective'));
        const wasm = run(a);
        expect({ out: nat.stdout, err: nat.stderr, status: nat.status }).toEqual({ out: wasm.stdout, err: wasm.stderr, status: wasm.status });
      }
    }
  });

  it.skipIf(!nativeHas('remesh'))('remesh --json: the native report, the same values but the timings', () => {
    const input = join(root, 'web', 'samples', 'icosphere.obj');
    const args = ['remesh', input, '--edge-length-rel', '0.1', '--no-hausdorff', '--json'];
    const wasm = run(args);
    const nat = spawnSync(native, args, { encoding: 'utf8' });
    expect(wasm.status).toBe(nat.status);
    const w = JSON.parse(wasm.stdout), n = JSON.parse(nat.stdout);
    expect(Object.keys(w)).toEqual(Object.keys(n));
    // one seconds key per stage of the table, in its order (include/conformesh/stages.h), in both
    expect(Object.keys(w.seconds)).toEqual([...REMESH_STAGES.map((s) => s.key), 'total']);
    expect(Object.keys(n.seconds)).toEqual(Object.keys(w.seconds));
    // Both builds compute the same bits (docs/ARCHITECTURE.md, "Determinism"): only the timings differ.
    delete w.seconds;
    delete n.seconds;
    expect(w).toEqual(n);
    // the text report: the same lines, the seconds' labels the table's
    const text = ['remesh', input, '--edge-length-rel', '0.1', '--no-hausdorff'];
    const numbers = (t: string) => t.replace(/[0-9]+\.[0-9]+/g, '#');
    const wasmText = numbers(run(text).stdout);
    expect(wasmText).toBe(numbers(spawnSync(native, text, { encoding: 'utf8' }).stdout));
    expect(wasmText).toContain(`${REMESH_STAGES.map((s) => `${s.label} #, `).join('')}total #`);
    if (!('error' in n)) {
      expect(n.topologyPreserved).toBe(true);
      expect(n.trianglesBelowBoundOutsideExempt).toBe(0);
    }
    // the optimizer's flags reach it: no passes is the unoptimized mesh, a pass count is honoured
    // alike in both builds
    const opt = (extra: string[]) => {
      const a = ['remesh', input, '--edge-length-rel', '0.1', '--no-hausdorff', '--json', ...extra];
      const [x, y] = [JSON.parse(run(a).stdout), JSON.parse(spawnSync(native, a, { encoding: 'utf8' }).stdout)];
      delete x.seconds;
      delete y.seconds;
      expect(x).toEqual(y);
      return x;
    };
    for (const bad of [['--optimize-iterations', '2.5'], ['--optimize-iterations', '-1'], ['--optimize-tolerance', '-0.1']]) {
      const a = ['remesh', input, ...bad, '--json'];
      const [x, y] = [JSON.parse(run(a).stdout), JSON.parse(spawnSync(native, a, { encoding: 'utf8' }).stdout)];
      // the same error; the wording comes from the JS options check or the C++ one
      expect([x.error.name, x.error.stage, y.error.name, y.error.stage]).toEqual(['InvalidArgument', 'api', 'InvalidArgument', 'api']);
      expect(x.error.message).toMatch(bad[0] === '--optimize-tolerance' ? /optimizeTolerance/ : /optimize-?[iI]terations/);
      if (bad[1] === '2.5') expect(x).toEqual(y);
    }
    const none = opt(['--optimize-iterations', '0']), off = opt(['--no-optimize']);
    expect(none.meanMinAngle).toBe(off.meanMinAngle);
    expect(none.optimizeMoves).toBe(0);
    opt(['--min-patch-width', '-1']);
    const more = opt(['--optimize-iterations', '4', '--optimize-tolerance', '0']);
    expect(more.optimizeMoves).toBeGreaterThanOrEqual(n.optimizeMoves);
    for (const bad of [
      ['remesh', input, '--edge-length', '1', '--edge-length-rel', '0.1', '--json'],
      ['remesh', input, '--boundary', 'disk', '--json'],
    ]) {
      const out = run(bad).stdout;
      expect(out).toBe(spawnSync(native, bad, { encoding: 'utf8' }).stdout);
      expect(JSON.parse(out).error.name).toBe('InvalidArgument');
    }
  });
});
