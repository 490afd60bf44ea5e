// Error-driven remeshing against CGAL isotropic remeshing at the same measured Hausdorff distance
// (issue: "the coarsest mesh within an error bound"). For every model of ../shared/data: ours at
// --max-error-rel R (default 1e-3), scored by the outside checker (meshq: raw angles, two-sided
// Hausdorff); then CGAL's isotropic_remeshing (sharp edges >= 60° constrained, 3 iterations) at
// target edge lengths searched (secant in log-log: Hausdorff ~ target²) until its measured
// Hausdorff distance brackets ours; CGAL's count at ours is interpolated in log-log between the
// bracketing runs. Writes bench/results/max-error-<timestamp>.md.
// With --defaults, ours runs at the default options instead (the edge length drives), for the
// count at equal accuracy at the defaults; the table goes to equal-hausdorff-<timestamp>.md.
// usage: node bench/max_error.mjs [--rel 1e-3 | --defaults] [--models a.off,b.obj] [--bin build/native/conformesh]
//   [--work DIR]   (its outputs; default bench/work/max-error: two runs at once need two)
//   needs build/tools/meshq (bench/models.sh builds it) and bench/work/peers/cgal_remesh (bench/run.sh)
import { execFileSync, spawnSync } from 'node:child_process';
import { mkdirSync, readdirSync, readFileSync, writeFileSync } from 'node:fs';
import path from 'node:path';

const ROOT = path.resolve(path.dirname(new URL(import.meta.url).pathname), '..');
const DATA = process.env.DATA ?? path.join(ROOT, '..', 'shared', 'data');
const arg = (name, fallback) => {
  const i = process.argv.indexOf(name);
  return i > 0 ? process.argv[i + 1] : fallback;
};
const REL = Number(arg('--rel', '1e-3'));
const DEFAULTS = process.argv.includes('--defaults');
const BIN = arg('--bin', path.join(ROOT, 'build/native/conformesh'));
const MESHQ = path.join(ROOT, 'build/tools/meshq');
const CGAL = path.join(ROOT, 'bench/work/peers/cgal_remesh');
const WORK = path.resolve(arg('--work', path.join(ROOT, 'bench/work/max-error')));
const CGAL_RUNS = 6;  // CGAL runs per model at most
mkdirSync(WORK, { recursive: true });
const only = (arg('--models', '') || '').split(',').filter(Boolean);
const models = readdirSync(DATA).filter((f) => /\.(obj|off|stl)$/i.test(f) && (!only.length || only.includes(f))).sort();

const meshq = (ref, cand) => JSON.parse(execFileSync(MESHQ, [ref, cand, '60'], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] }));
const hausdorff = (q) => Math.max(q.hausdorff_rel.cand_to_ref, q.hausdorff_rel.ref_to_cand);

const rows = [];
for (const model of models) {
  const input = path.join(DATA, model), base = model.replace(/\.[^.]+$/, '');
  const row = { model };
  const ours = path.join(WORK, `${base}-ours.obj`);
  const t0 = Date.now();
  const r = spawnSync(BIN, ['remesh', input, '-o', ours, ...(DEFAULTS ? [] : ['--max-error-rel', String(REL)]), '--json'], { encoding: 'utf8', timeout: 600000 });
  row.oursSeconds = (Date.now() - t0) / 1000;
  let rep;
  try { rep = JSON.parse(r.stdout); } catch { rep = { error: { name: 'crash', message: r.stderr.slice(0, 200) } }; }
  if (rep.error) { row.error = `${rep.error.name}: ${rep.error.message}`; rows.push(row); console.log(model, row.error); continue; }
  const q = meshq(input, ours);
  Object.assign(row, { triangles: q.cand.f, hausdorff: hausdorff(q), rawMin: q.cand.min_angle, minOutsideExempt: rep.minAngleOutsideExempt,
    belowOutsideExempt: rep.trianglesBelowBoundOutsideExempt, meanMin: q.cand.mean_min_angle, kept60: q.features.kept_pct, attempts: rep.warnings.filter((w) => w.startsWith('max error:')).length });
  // CGAL at the same measured distance
  const runs = [];
  let t = 0.004;
  for (let i = 0; i < CGAL_RUNS; ++i) {
    const out = path.join(WORK, `${base}-cgal.off`);
    const c = spawnSync(CGAL, [input, '-o', out, '--edge-length-rel', String(t), '--feature-angle', '60', '--iterations', '3'], { encoding: 'utf8', timeout: 600000 });
    if (c.status !== 0) break;
    const cq = meshq(input, out);
    runs.push({ t, triangles: cq.cand.f, hausdorff: hausdorff(cq), rawMin: cq.cand.min_angle });
    const below = runs.filter((x) => x.hausdorff <= row.hausdorff), above = runs.filter((x) => x.hausdorff > row.hausdorff);
    if (below.length && above.length && Math.abs(Math.log(runs.at(-1).hausdorff / row.hausdorff)) < 0.1) break;
    t *= Math.sqrt(row.hausdorff / runs.at(-1).hausdorff);  // Hausdorff ~ target²
    t = Math.min(Math.max(t, 2e-4), 0.1);
  }
  const below = runs.filter((x) => x.hausdorff <= row.hausdorff).sort((a, b) => b.hausdorff - a.hausdorff)[0];
  const above = runs.filter((x) => x.hausdorff > row.hausdorff).sort((a, b) => a.hausdorff - b.hausdorff)[0];
  row.cgalRuns = runs;
  if (below && above) {
    // log-log interpolation of CGAL's count at our distance
    const s = Math.log(row.hausdorff / below.hausdorff) / Math.log(above.hausdorff / below.hausdorff);
    const n = Math.round(Math.exp(Math.log(below.triangles) + s * Math.log(above.triangles / below.triangles)));
    if (Number.isFinite(n)) row.cgalTriangles = n;
  } else if (below) row.cgalTrianglesAtMost = below.triangles;  // CGAL reached our distance with this many
  rows.push(row);
  console.log(model, JSON.stringify({ ...row, cgalRuns: undefined }));
}
const ratio = (x) => (x.cgalTriangles ? x.triangles / x.cgalTriangles : null);
const ratios = rows.map(ratio).filter((x) => x);
const geomean = ratios.length ? Math.exp(ratios.reduce((s, x) => s + Math.log(x), 0) / ratios.length) : NaN;
const f = (x, d) => (x === undefined || x === null ? '' : typeof x === 'number' ? x.toFixed(d) : String(x));
const lines = [
  `# ${DEFAULTS ? 'Ours at the default options' : `Error-driven remeshing at --max-error-rel ${REL}`} against CGAL isotropic remeshing at the same measured Hausdorff distance (${new Date().toISOString().slice(0, 10)}, ${BIN}, the tree at ${execFileSync('git', ['rev-parse', '--short', 'HEAD'], { cwd: ROOT, encoding: 'utf8' }).trim()} when written)`,
  '',
  'Hausdorff distances (relative to the diagonal) and raw angles by meshq (../shared/tools/meshq.cpp); CGAL count interpolated in log-log between its runs bracketing our distance. Ours/CGAL geometric mean: ' + f(geomean, 3),
  '',
  '| model | ours: triangles | Hausdorff | ≤ bound | raw min ∠ | min ∠ outside exempt | below bound outside exempt | mean min ∠ | 60° kept % | attempts | s | CGAL triangles at our distance | ours / CGAL | CGAL raw min ∠ |',
  '|---|---|---|---|---|---|---|---|---|---|---|---|---|---|',
  ...rows.map((x) => x.error ? `| ${x.model} | ${x.error} |||||||||||||` :
    `| ${x.model} | ${x.triangles} | ${x.hausdorff.toExponential(2)} | ${DEFAULTS ? '—' : x.hausdorff <= REL ? 'yes' : '**no**'} | ${f(x.rawMin, 2)} | ${f(x.minOutsideExempt, 2)} | ${x.belowOutsideExempt} | ${f(x.meanMin, 2)} | ${f(x.kept60, 1)} | ${x.attempts} | ${f(x.oursSeconds, 1)} | ${x.cgalTriangles ?? (x.cgalTrianglesAtMost ? '≤ ' + x.cgalTrianglesAtMost : 'not bracketed')} | ${f(ratio(x), 2)} | ${f(x.cgalRuns[0]?.rawMin, 2)} |`),
];
const file = path.join(ROOT, 'bench/results', `${DEFAULTS ? 'equal-hausdorff' : 'max-error'}-${new Date().toISOString().replace(/[-:]/g, '').slice(0, 15)}.md`);
writeFileSync(file, lines.join('\n') + '\n');
console.log(lines.join('\n'));
console.log(`written ${file}`);
