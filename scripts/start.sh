#!/usr/bin/env bash
# `npm start`'s main job (until the remesh pipeline exists): load every mesh of the embedded
# sample set (web/samples, made by `conformesh generate`) and of ../shared/data when present,
# validate it, and print one row per mesh: V, F, components, boundary loops, χ, genus, warnings.
# Exit status 1 if any mesh fails to load.
set -euo pipefail
cd "$(dirname "$0")/.."
EXE=build/native/conformesh
if [ ! -x "$EXE" ]; then
  echo "start: $EXE is missing; run scripts/build.sh first" >&2
  exit 1
fi

# The remesh pipeline on the embedded default model: a cube made by our own generator, remeshed
# with the defaults (edge length 1% of the diagonal, min angle 30 degrees); the report as a table.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$EXE" generate cube -o "$tmp/cube.obj" --level 3 >/dev/null
echo "conformesh: remesh of the default model (generated cube, defaults)"
echo
"$EXE" remesh "$tmp/cube.obj" -o "$tmp/cube-remeshed.obj"
echo

files=(web/samples/*.obj web/samples/*.off web/samples/*.stl web/samples/*.ply)
if [ -d ../shared/data ]; then
  for f in ../shared/data/*; do
    case "$f" in *.obj|*.off|*.stl|*.ply) files+=("$f") ;; esac
  done
fi

# One JSON line per file: {"file": ..., "report": <conformesh info --json output>}.
lines=""
for f in "${files[@]}"; do
  [ -f "$f" ] || continue
  out=$("$EXE" info "$f" --json || true)
  lines+="{\"file\":\"$f\",\"report\":${out:-null}}"$'\n'
done

printf '%s' "$lines" | node -e '
const rows = require("fs").readFileSync(0, "utf8").trim().split("\n").map((l) => JSON.parse(l));
const head = ["file", "V", "F", "comp", "loops", "χ", "genus", "warnings"];
const table = [head];
let failed = 0;
for (const { file, report: r } of rows) {
  const name = file.replace(/^web\/samples\//, "samples/").replace(/^\.\.\/shared\/data\//, "data/");
  if (!r || r.error) {
    failed++;
    table.push([name, "error: " + (r ? r.error.name + ": " + r.error.message : "no output"), "", "", "", "", "", ""]);
    continue;
  }
  const warn = r.warnings.map((w) => (w.code === "Ok" ? "note" : w.code) + (w.count > 1 ? "×" + w.count : "")).join(", ") || "-";
  table.push([name, r.vertices, r.faces, r.components, r.boundaryLoops, r.euler, r.genus, warn].map(String));
}
const width = head.map((_, i) => Math.max(...table.map((row) => [...(row[i] ?? "")].length)));
const pad = (s, w, right) => (right ? s.padStart(w) : s.padEnd(w));
console.log("conformesh: validation and topology of the sample meshes (conformesh info)\n");
table.forEach((row, k) => {
  // file left-aligned, numbers right-aligned, warnings last and unpadded
  console.log(row.map((c, i) => (i === 7 ? c : pad(c, width[i], i > 0))).join("  "));
  if (k === 0) console.log(width.map((w) => "-".repeat(w)).join("  "));
});
console.log(`\n${rows.length - failed} of ${rows.length} meshes loaded` + (failed ? `, ${failed} failed` : ""));
process.exit(failed ? 1 : 0);
'
