#!/usr/bin/env bash
# --min-angle 35 against the defaults (30°) on every model of ../shared/data: each model run three
# times at each bound, interleaved, with --threads 2; the seconds are the best of three (wall), the
# counts and angles from the last run's report. Prints a markdown table (bench/results/deg35-*.md).
# usage: bash bench/bound35.sh BIN OUTDIR   (MODELS="a.off b.obj" for a subset)
set -u
cd "$(dirname "$0")/.."
BIN=$1; OUT=$2; mkdir -p "$OUT"
DATA=${DATA:-../shared/data}
MODELS=${MODELS:-$(cd "$DATA" && ls *.off *.obj *.stl 2>/dev/null | tr '\n' ' ')}
echo "| model | triangles at 30° | at 35° | ratio | below 35° outside exempt corners | min ∠ outside exempt | mean min ∠ at 35° (report) | s at 30° | s at 35° | time ratio |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for m in $MODELS; do
  b=${m%.*}
  best30=-1; best35=-1
  for i in 1 2 3; do
    for a in 30 35; do
      s=$(date +%s%N)
      "$BIN" remesh "$DATA/$m" -o "$OUT/$b.$a.obj" --json --min-angle $a --threads 2 > "$OUT/$b.$a.json" 2>/dev/null
      e=$(date +%s%N)
      t=$(( (e - s) / 1000000 ))
      if [ $a = 30 ]; then
        if [ $best30 -lt 0 ] || [ $t -lt $best30 ]; then best30=$t; fi
      elif [ $best35 -lt 0 ] || [ $t -lt $best35 ]; then
        best35=$t
      fi
    done
  done
  node -e 'const fs=require("fs");const a=JSON.parse(fs.readFileSync(process.argv[1])),b=JSON.parse(fs.readFileSync(process.argv[2]));const t30=+process.argv[4]/1000,t35=+process.argv[5]/1000;
  console.log(`| ${process.argv[3]} | ${a.triangles} | ${b.triangles} | ${(b.triangles/a.triangles).toFixed(2)} | ${b.trianglesBelowBoundOutsideExempt} | ${b.minAngleOutsideExempt.toFixed(2)} | ${b.meanMinAngle.toFixed(2)} | ${t30.toFixed(2)} | ${t35.toFixed(2)} | ${(t35/t30).toFixed(2)} |`)' \
    "$OUT/$b.30.json" "$OUT/$b.35.json" "$m" $best30 $best35
done
