#!/usr/bin/env bash
# The robustness sweep: every model of ../shared/data remeshed at every combination of
# --feature-angle and --edge-length-rel with the native CLI, each run capped at 30 s. One row per
# run: the status (ok or the error's code name), triangles, the smallest angle outside exempt
# corners, the triangles below the bound there, topology, seconds. Writes
# bench/results/sweep-<timestamp>.md and prints a summary.
# usage: bash bench/sweep.sh [BIN]   (MODELS="a.off b.obj", ANGLES="20 45", LENGTHS="0.01")
set -u
cd "$(dirname "$0")/.."
BIN=${1:-build/native/conformesh}
DATA=${DATA:-../shared/data}
ANGLES=${ANGLES:-"20 30 45 60 90"}
LENGTHS=${LENGTHS:-"0.005 0.01 0.02"}
MODELS=${MODELS:-$(cd "$DATA" && ls *.off *.obj *.stl 2>/dev/null | tr '\n' ' ')}
CAP=${CAP:-30}
OUT=bench/results/sweep-$(date -u +%Y-%m-%dT%H%M%S).md
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
{
  echo "# Sweep: --feature-angle × --edge-length-rel over ../shared/data ($(date -u +%Y-%m-%d), $(git rev-parse --short HEAD 2>/dev/null))"
  echo
  echo "Each run capped at ${CAP} s. Status: ok, or the error's code name (a broken output is an error)."
  echo
  echo "| model | feature angle | edge rel | status | triangles | min ∠ outside exempt | below bound outside exempt | topology | s |"
  echo "|---|---|---|---|---|---|---|---|---|"
} > "$OUT"
runs=0 ok=0 slow=0 broken=0
for m in $MODELS; do
  for a in $ANGLES; do
    for l in $LENGTHS; do
      runs=$((runs + 1))
      s=$(date +%s%N)
      timeout "$CAP" "$BIN" remesh "$DATA/$m" -o "$TMP/out.obj" --json --no-hausdorff --feature-angle "$a" --edge-length-rel "$l" > "$TMP/r.json" 2> /dev/null
      rc=$?
      ms=$(( ($(date +%s%N) - s) / 1000000 ))
      row=$(node -e '
        const fs = require("fs");
        const [file, rc, ms] = [process.argv[1], +process.argv[2], +process.argv[3]];
        let r = {};
        try { r = JSON.parse(fs.readFileSync(file, "utf8")); } catch (e) {}
        const s = (ms / 1000).toFixed(1);
        if (rc === 124) { console.log(`timeout|||||${s}`); process.exit(); }
        if (r.error) { console.log(`${r.error.name}|||||${s}`); process.exit(); }
        if (!r.triangles) { console.log(`exit ${rc}|||||${s}`); process.exit(); }
        console.log(`ok|${r.triangles}|${r.minAngleOutsideExempt.toFixed(2)}|${r.trianglesBelowBoundOutsideExempt}|${r.topologyPreserved ? "kept" : "BROKEN"}|${s}`);
      ' "$TMP/r.json" "$rc" "$ms")
      IFS='|' read -r status tris minout below topo secs <<< "$row"
      [ "$status" = ok ] && ok=$((ok + 1))
      [ "$status" = timeout ] && slow=$((slow + 1))
      [ "$topo" = BROKEN ] && broken=$((broken + 1))
      echo "| $m | $a | $l | $status | $tris | $minout | $below | $topo | $secs |" >> "$OUT"
    done
  done
done
echo "" >> "$OUT"
echo "$runs runs: $ok ok, $slow over ${CAP} s, $broken with broken topology reported as success." | tee -a "$OUT"
echo "table: $OUT"
