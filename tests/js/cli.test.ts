// The package CLI (dist/cli.js, the `conformesh` bin) running the WASM module in Node: output,
// exit codes and JSON shapes; and, when the native CLI has the same command, identical output.
import { execFileSync, spawnSync } from 'node:child_process';
import { existsSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { init } from '../../dist/index.js';
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
