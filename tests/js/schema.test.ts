// One table of remesh's options and report fields (include/conformesh/remesh_schema.h): every option and every
// report field is in the module's export, the TypeScript key lists (which tsc checks against the
// RemeshOptions and RemeshReport types), both CLIs' --help and --json, and reaches the C++ side.
import { spawnSync } from 'node:child_process';
import { existsSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { ConformeshError, EXEMPT_CORNER_KEYS, init, REMESH_OPTION_KEYS, REMESH_REPORT_KEYS } from '../../dist/index.js';
import { root } from './helpers.js';

const cli = join(root, 'dist', 'cli.js');
const native = join(root, 'build', 'native', 'conformesh');
const input = join(root, 'web', 'samples', 'icosphere.obj');
/** Options only the library API has: they shape the returned arrays, which a CLI does not write. */
const API_ONLY = ['patches', 'surfacePoints'];

const clis = [
  { name: 'package', run: (args: string[]) => spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8' }) },
  { name: 'native', run: (args: string[]) => spawnSync(native, args, { encoding: 'utf8' }) },
];

describe('remesh schema: one table for options and report', () => {
  it('the module exports the same option and report names as the TypeScript key lists', async () => {
    const schema = (await init()).remeshSchema();
    expect(schema.options.map((o) => o.name).sort()).toEqual([...REMESH_OPTION_KEYS].sort());
    expect(schema.report).toEqual([...REMESH_REPORT_KEYS]);
    expect(schema.exemptCorner).toEqual([...EXEMPT_CORNER_KEYS]);
    for (const o of schema.options) {
      expect(o.flag === '', `${o.name}: no CLI flag`).toBe(API_ONLY.includes(o.name));
      expect(o.help.length, `${o.name}: help`).toBeGreaterThan(10);
    }
  });

  it('every option reaches the C++ conversion: a value of the wrong type is rejected by name', async () => {
    const cm = await init();
    const mesh = cm.readMesh(new Uint8Array(await import('node:fs').then((fs) => fs.readFileSync(input))), 'obj');
    for (const name of REMESH_OPTION_KEYS) {
      let error: unknown;
      try {
        cm.remesh(mesh, { [name]: name === 'boundary' ? 'nowhere' : 'x' } as never);
      } catch (e) {
        error = e;
      }
      expect(error, name).toBeInstanceOf(ConformeshError);
      expect((error as ConformeshError).code, name).toBe('InvalidArgument');
      expect((error as ConformeshError).message, name).toContain(name);
    }
  });

  it('a remesh report has exactly the table\'s fields, and an exempt corner the corner\'s', async () => {
    const cm = await init();
    // a flat triangle with a 10 degree corner at vertex 0, split twice at its edge midpoints
    let positions = [0, 0, 0, 1, -0.0875, 0, 1, 0.0875, 0];
    let triangles = [0, 1, 2];
    for (let round = 0; round < 2; ++round) {
      const next: number[] = [];
      const mid = new Map<string, number>();
      const m = (a: number, b: number) => {
        const key = `${Math.min(a, b)},${Math.max(a, b)}`;
        if (!mid.has(key)) {
          mid.set(key, positions.length / 3);
          for (let k = 0; k < 3; ++k) positions.push((positions[3 * a + k]! + positions[3 * b + k]!) / 2);
        }
        return mid.get(key)!;
      };
      for (let t = 0; t < triangles.length; t += 3) {
        const [a, b, c] = [triangles[t]!, triangles[t + 1]!, triangles[t + 2]!];
        const [ab, bc, ca] = [m(a, b), m(b, c), m(c, a)];
        next.push(a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca);
      }
      triangles = next;
    }
    const r = cm.remesh({ positions, triangles }, { targetEdgeLengthRel: 0.03, computeHausdorff: false });
    expect(Object.keys(r.report)).toEqual([...REMESH_REPORT_KEYS]);
    expect(r.report.exemptCorners.length).toBe(1);
    for (const c of r.report.exemptCorners) expect(Object.keys(c)).toEqual([...EXEMPT_CORNER_KEYS]);
    expect(r.report.exemptCorners[0]!.vertex).toBe(0);
  });

  for (const c of clis) {
    it.skipIf(c.name === 'native' && !existsSync(native))(`${c.name} CLI: --help lists every option's flag, --json every report field`, async () => {
      const schema = (await init()).remeshSchema();
      const help = c.run(['remesh', '--help']);
      expect(help.status).toBe(0);
      const listed = new Set([...help.stdout.matchAll(/^ {2}(--?[a-z][a-z0-9-]*)/gm)].map((m) => m[1]!));
      for (const o of schema.options.filter((o) => o.flag !== '')) expect(listed.has(o.flag), `${o.name}: ${o.flag} in --help`).toBe(true);
      const json = c.run(['remesh', input, '--edge-length-rel', '0.1', '--no-hausdorff', '--json']);
      expect(json.status).toBe(0);
      expect(Object.keys(JSON.parse(json.stdout))).toEqual([...REMESH_REPORT_KEYS]);
    });
  }
});
