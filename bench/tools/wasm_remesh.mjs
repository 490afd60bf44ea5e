// WASM remesh timing for the bench's wasm section (issue 6): the package's own module under Node,
// the same call repeated in one process. Prints one JSON line per call and a summary line:
//   {"run":i,"seconds":s,"triangles":n}   ...   {"first":s0,"seconds":median of the later calls,"init":s}
// usage: node bench/tools/wasm_remesh.mjs IN EDGE_REL REPEAT
import { readFileSync } from 'node:fs';
import { performance } from 'node:perf_hooks';
import { init } from '../../dist/index.js';

const [input, relArg = '0.004', repeatArg = '3'] = process.argv.slice(2);
if (!input) {
  console.error('usage: node bench/tools/wasm_remesh.mjs IN EDGE_REL REPEAT');
  process.exit(2);
}
const repeat = Math.max(2, Number(repeatArg));
const t0 = performance.now();
const cm = await init();
const initSeconds = (performance.now() - t0) / 1000;
const mesh = cm.readMesh(readFileSync(input), { fileName: input });
const times = [];
for (let i = 0; i < repeat; ++i) {
  const t = performance.now();
  const r = cm.remesh(mesh, { targetEdgeLengthRel: Number(relArg), computeHausdorff: false });
  const s = (performance.now() - t) / 1000;
  times.push(s);
  console.log(JSON.stringify({ run: i, seconds: s, triangles: r.report.triangles, reported: r.report.seconds.total }));
}
const later = times.slice(1).sort((a, b) => a - b);
console.log(JSON.stringify({ first: times[0], seconds: later[Math.floor(later.length / 2)], init: initSeconds }));
