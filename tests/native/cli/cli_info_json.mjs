// CTest: `conformesh info --json` on every mesh in shared/data (against its MANIFEST), on the
// shipped samples (against web/samples/samples.json), on bad files (error object, exit code),
// and the human table.
// usage: node cli_info_json.mjs CONFORMESH_EXE DATA_DIR SAMPLES_DIR
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { check, finish } from './check.mjs';

const [exe, dataDir, samplesDir] = process.argv.slice(2);
const KEYS = ['vertices', 'faces', 'components', 'boundaryLoops', 'euler', 'genus', 'nonManifoldEdges',
  'degenerateFaces', 'warnings'];

function info(file, json = true) {
  const r = spawnSync(exe, ['info', file, ...(json ? ['--json'] : [])], { encoding: 'utf8' });
  if (!json) return r;
  let parsed = null;
  try {
    parsed = JSON.parse(r.stdout);
  } catch (e) {
    check(false, `${file}: stdout is not JSON: ${r.stdout.slice(0, 200)}`);
  }
  return { status: r.status, json: parsed };
}

function checkReport(file, rep) {
  check(JSON.stringify(Object.keys(rep).sort()) === JSON.stringify([...KEYS].sort()),
    `${file}: keys are exactly ${KEYS.join(', ')} (got ${Object.keys(rep).join(', ')})`);
  for (const k of KEYS.slice(0, -1)) check(typeof rep[k] === 'number', `${file}: ${k} is a number`);
  check(Array.isArray(rep.warnings), `${file}: warnings is an array`);
  for (const w of rep.warnings ?? [])
    check(typeof w.code === 'string' && typeof w.message === 'string' && typeof w.count === 'number',
      `${file}: warning has code, count, message`);
}

// shared/data against its MANIFEST.
const manifest = join(dataDir, 'MANIFEST.md');
if (existsSync(manifest)) {
  let cols = null;
  let rows = 0;
  for (const line of readFileSync(manifest, 'utf8').split('\n')) {
    if (!line.startsWith('|')) continue;
    const c = line.split('|').slice(1, -1).map((s) => s.trim());
    if (c[0] === 'file') {
      cols = Object.fromEntries(c.map((name, i) => [name, i]));
      continue;
    }
    if (!cols || c[0].startsWith('---')) continue;
    const file = c[0];
    const { status, json } = info(join(dataDir, file));
    check(status === 0, `${file}: exit code 0`);
    if (!json) continue;
    rows++;
    checkReport(file, json);
    const want = { vertices: 'V', faces: 'F', boundaryLoops: 'bnd loops', euler: 'chi', genus: 'genus' };
    for (const [key, col] of Object.entries(want))
      check(json[key] === Number(c[cols[col]]), `${file}: ${key} = ${json[key]}, MANIFEST says ${c[cols[col]]}`);
    // the MANIFEST's genus = (2·components − chi − loops) / 2 gives its components (ALSTOM_TEST4: 6)
    const components = (Number(c[cols.chi]) + Number(c[cols['bnd loops']]) + 2 * Number(c[cols.genus])) / 2;
    check(json.nonManifoldEdges === 0 && json.degenerateFaces === 0 && json.components === components,
      `${file}: manifold, no degenerate faces, ${components} components`);
  }
  check(rows >= 12, `MANIFEST rows checked: ${rows}`);
} else {
  console.log(`no data at ${dataDir}: MANIFEST checks skipped`);
}

// The shipped samples.
const samples = JSON.parse(readFileSync(join(samplesDir, 'samples.json'), 'utf8')).meshes;
for (const [file, want] of Object.entries(samples)) {
  const { status, json } = info(join(samplesDir, file));
  check(status === 0, `${file}: exit code 0`);
  if (!json) continue;
  checkReport(file, json);
  for (const [k, v] of Object.entries(want)) check(json[k] === v, `${file}: ${k} = ${json[k]}, expected ${v}`);
}
{
  const { json } = info(join(samplesDir, 'needs-repair.obj'));
  const codes = (json?.warnings ?? []).map((w) => w.code);
  check(codes.includes('DegenerateFace') && codes.includes('InconsistentOrientation'),
    `needs-repair.obj: warnings name DegenerateFace and InconsistentOrientation (got ${codes})`);
}

// Bad files: a non-zero exit and {"error":{"code","name","stage","message"}} on stdout.
const dir = mkdtempSync(join(tmpdir(), 'conformesh-cli-'));
try {
  const bad = {
    'missing.obj': [null, 'IoError'],
    'empty.obj': ['', null],
    'index.obj': ['v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n', 'IndexOutOfRange'],
    'noise.stl': [String.fromCharCode(...Array.from({ length: 300 }, (_, i) => (i * 7919) % 256)), null],
  };
  for (const [name, [content, code]] of Object.entries(bad)) {
    const path = join(dir, name);
    if (content !== null) writeFileSync(path, content, 'latin1');
    const { status, json } = info(path);
    check(status !== 0, `${name}: non-zero exit`);
    const e = json?.error;
    check(e && typeof e.code === 'number' && typeof e.message === 'string' && typeof e.name === 'string',
      `${name}: {"error":{"code","message",...}} (got ${JSON.stringify(json)})`);
    if (code) check(e?.name === code, `${name}: error ${code} (got ${e?.name})`);
  }
  // The generated samples are reproducible: `conformesh generate` (commands in web/samples/README.md)
  // writes the same file: the same bytes for binary formats, the same tokens and the same doubles
  // for text formats (a number may be printed differently and still parse to the same double).
  const sameMesh = (a, b, text) => {
    if (!text) return a.equals(b);
    const ta = a.toString('latin1').split(/\s+/), tb = b.toString('latin1').split(/\s+/);
    return ta.length === tb.length && ta.every((x, i) => x === tb[i] || (x !== '' && Number(x) === Number(tb[i])));
  };
  const readme = readFileSync(join(samplesDir, 'README.md'), 'utf8');
  for (const m of readme.matchAll(/`conformesh generate (\S+) --level (\d+) -o (\S+)`/g)) {
    const [, shape, level, file] = m;
    const out = join(dir, file);
    const r = spawnSync(exe, ['generate', shape, '--level', level, '-o', out], { encoding: 'utf8' });
    check(r.status === 0, `generate ${shape}: exit 0 (${r.stderr})`);
    check(r.status === 0 && sameMesh(readFileSync(out), readFileSync(join(samplesDir, file)), /\.(obj|off)$/.test(file)),
      `generate ${shape} --level ${level} reproduces web/samples/${file}`);
  }
  // A non-manifold edge is counted, not fatal.
  const fin = join(dir, 'fin.obj');
  writeFileSync(fin, 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 1\nf 1 2 3\nf 1 3 4\nf 3 1 5\n');
  const { status, json } = info(fin);
  check(status === 0 && json?.nonManifoldEdges === 1, `fin.obj: exit 0 and nonManifoldEdges 1 (got ${JSON.stringify(json)})`);
} finally {
  rmSync(dir, { recursive: true, force: true });
}

// The human format: one aligned row per key.
{
  const r = info(join(samplesDir, 'torus.off'), false);
  check(r.status === 0, 'human format: exit code 0');
  for (const k of KEYS) check(new RegExp(`^${k} +\\S`, 'm').test(r.stdout), `human format has a row '${k}'`);
}

finish();
