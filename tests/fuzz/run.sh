#!/usr/bin/env bash
# npm run fuzz — build the libFuzzer harnesses (clang 14, ASan + UBSan) and run each for a set time.
#
#   FUZZ_SECONDS=60 FUZZ_TARGETS="auto obj" bash tests/fuzz/run.sh
#
# FUZZ_SECONDS: seconds per target (default 60; FUZZ_SECONDS_REMESH for remesh, default the same).
# FUZZ_TARGETS: a subset of the targets below
# (the readers, and `remesh`: fuzz_remesh.cpp on small meshes decoded from the bytes, whose
# findings go to tests/data/fuzz-regressions-remesh and are replayed by
# tests/native/remesh/fuzz_regressions_test.cpp).
# Corpora live in build/fuzz/corpus/<target> (kept between runs: they grow), seeded from small
# valid files written by tests/fuzz/make_seeds.cpp; the regression inputs in
# tests/data/fuzz-regressions are replayed first. A crash, leak, timeout or out-of-memory input is
# copied into tests/data/fuzz-regressions/ (the doctest fuzz_regressions_bad_input_test.cpp then
# reads it under ASan/UBSan in every `npm test`). Summary: build/fuzz/summary.json and
# bench/results/fuzz-latest.json. Exit code 1 when any target found a problem.
set -uo pipefail
cd "$(dirname "$0")/../.."
ROOT="$(pwd)"
OUT="$ROOT/build/fuzz"
SECONDS_EACH="${FUZZ_SECONDS:-60}"
# remesh runs about 20–40 inputs per second (readers: thousands): its own time, default the same
SECONDS_REMESH="${FUZZ_SECONDS_REMESH:-$SECONDS_EACH}"
CXX="${FUZZ_CXX:-clang++-14}"
# clang 14 and its libFuzzer/sanitizer runtimes (Debian 12: clang-14, libclang-rt-14-dev).
need=()
command -v clang++-14 >/dev/null 2>&1 || need+=(clang-14)
dpkg -s libclang-rt-14-dev >/dev/null 2>&1 || need+=(libclang-rt-14-dev)
if [ -z "${FUZZ_CXX:-}" ] && [ ${#need[@]} -gt 0 ]; then
  echo "fuzz: installing ${need[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -q && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q "${need[@]}" \
    || { echo "fuzz: could not install ${need[*]}"; exit 2; }
fi
command -v "$CXX" >/dev/null 2>&1 || { echo "fuzz: $CXX not found"; exit 2; }

# target name : MeshFormat enumerator
# (remesh: the whole pipeline, not a reader)
ALL_TARGETS="auto:Auto obj:Obj off:Off stl-ascii:StlAscii stl-binary:StlBinary ply-ascii:PlyAscii ply-le:PlyBinaryLE ply-be:PlyBinaryBE remesh:-"
WANT="${FUZZ_TARGETS:-}"
wanted() { [ -z "$WANT" ] || [[ " $WANT " == *" $1 "* ]]; }
mkdir -p "$OUT/obj" "$OUT/bin" "$OUT/seeds" "$OUT/corpus" "$OUT/artifacts" "$OUT/logs" "$ROOT/tests/data/fuzz-regressions" \
  "$ROOT/tests/data/fuzz-regressions-remesh"

SAN="-fsanitize=address,undefined -fno-sanitize-recover=all"
CXXFLAGS="-std=c++17 -O1 -g -fno-omit-frame-pointer -I$ROOT/include -I$ROOT/src -isystem /usr/include/eigen3"

# ---- build: the readers (and what they use) instrumented for coverage --------------------------
echo "== fuzz: building with $CXX (ASan + UBSan + libFuzzer)"
objs=()
# (src/mesh uses the exact orient2d of src/planar/predicates.cpp, which needs -ffp-contract=off)
for src in "$ROOT"/src/core/*.cpp "$ROOT"/src/mesh/*.cpp "$ROOT"/src/planar/predicates.cpp; do
  obj="$OUT/obj/$(basename "${src%.cpp}").o"
  if [ ! -f "$obj" ] || [ "$src" -nt "$obj" ] || [ -n "$(find "$ROOT/src" -name '*.h' -newer "$obj" -print -quit)" ]; then
    $CXX $CXXFLAGS $SAN -ffp-contract=off -fsanitize=fuzzer-no-link -c "$src" -o "$obj" || { echo "fuzz: compile failed: $src"; exit 2; }
  fi
  objs+=("$obj")
done
$CXX $CXXFLAGS $SAN "$ROOT/tests/fuzz/make_seeds.cpp" "${objs[@]}" -o "$OUT/bin/make_seeds" \
  || { echo "fuzz: make_seeds did not build"; exit 2; }
for entry in $ALL_TARGETS; do
  name="${entry%%:*}"
  fmt="${entry##*:}"
  [ "$name" = remesh ] && continue
  extra=""
  [ "$name" = auto ] && extra="-DFUZZ_WELD=1"
  bin="$OUT/bin/fuzz_read_$name"
  if [ ! -x "$bin" ] || [ "$ROOT/tests/fuzz/fuzz_read_mesh.cpp" -nt "$bin" ] || [ -n "$(find "$OUT/obj" -newer "$bin" -print -quit)" ]; then
    $CXX $CXXFLAGS $SAN -fsanitize=fuzzer -DFUZZ_FORMAT="$fmt" $extra "$ROOT/tests/fuzz/fuzz_read_mesh.cpp" "${objs[@]}" -o "$bin" \
      || { echo "fuzz: harness $name did not build"; exit 2; }
  fi
done
rm -rf "$OUT/seeds" && mkdir -p "$OUT/seeds"
"$OUT/bin/make_seeds" "$OUT/seeds" || exit 2

# ---- build: the remesh harness (the rest of the library, instrumented) ---------------------------
if wanted remesh; then
  for src in "$ROOT"/src/features/*.cpp "$ROOT"/src/conformal/*.cpp "$ROOT"/src/planar/*.cpp \
             "$ROOT"/src/quality/*.cpp "$ROOT"/src/remesh/*.cpp; do
    [ "$src" = "$ROOT/src/planar/predicates.cpp" ] && continue  # built with the readers
    obj="$OUT/obj/$(basename "$(dirname "$src")")_$(basename "${src%.cpp}").o"
    if [ ! -f "$obj" ] || [ "$src" -nt "$obj" ] || [ -n "$(find "$ROOT/src" -name '*.h' -newer "$obj" -print -quit)" ]; then
      # -O2 for the pipeline (Eigen above all): the sanitizers slow it enough at -O1
      $CXX $CXXFLAGS -O2 $SAN -ffp-contract=off -fsanitize=fuzzer-no-link -c "$src" -o "$obj" || { echo "fuzz: compile failed: $src"; exit 2; }
    fi
    objs+=("$obj")
  done
  bin="$OUT/bin/fuzz_remesh"
  if [ ! -x "$bin" ] || [ "$ROOT/tests/fuzz/fuzz_remesh.cpp" -nt "$bin" ] || \
     [ "$ROOT/tests/native/remesh/fuzz_remesh_input.h" -nt "$bin" ] || [ -n "$(find "$OUT/obj" -newer "$bin" -print -quit)" ]; then
    $CXX $CXXFLAGS $SAN -fsanitize=fuzzer -I"$ROOT/tests/native" "$ROOT/tests/fuzz/fuzz_remesh.cpp" "${objs[@]}" -o "$bin" \
      || { echo "fuzz: harness remesh did not build"; exit 2; }
  fi
  # seeds: a flat 2 × 2 grid, a bumpy 4 × 4 grid with a hole, a tetrahedron from the random mode
  mkdir -p "$OUT/seeds/remesh"
  printf '\x20\x00\x01\x01' > "$OUT/seeds/remesh/flat"
  printf '\x12\x00\x03\x03\x04\x01\x00\x05\x02\x09\x03\x00\x01\x04\x02\x07\x04\x00\x00\x02\x00\x00\x00\x10\x00\x00' > "$OUT/seeds/remesh/bumpy"
  printf '\x30\x01\x01\x00\x01\x04\x10\x03\x00\x02\x01\x00\x01\x03\x01\x02\x03\x02\x00\x03' > "$OUT/seeds/remesh/tetra"
fi

# ---- run ---------------------------------------------------------------------------------------
summary="$OUT/summary.json"
echo "{\"started\":\"$(date -u +%FT%TZ)\",\"secondsPerTarget\":$SECONDS_EACH,\"secondsRemesh\":$SECONDS_REMESH,\"compiler\":\"$($CXX --version | head -1)\",\"cpu\":\"$(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')\",\"nproc\":$(nproc),\"targets\":[" > "$summary"
first=1
failed=0
printf "\n%-11s %12s %8s %10s %8s  %s\n" target executions seconds exec/s corpus result
for entry in $ALL_TARGETS; do
  name="${entry%%:*}"
  wanted "$name" || continue
  corpus="$OUT/corpus/$name"
  art="$OUT/artifacts/$name/"
  logf="$OUT/logs/$name.log"
  mkdir -p "$corpus" "$art"
  seeds="$OUT/seeds/$name"
  [ -d "$seeds" ] || seeds="$OUT/seeds/auto"
  regressions="$ROOT/tests/data/fuzz-regressions"
  t0=$(date +%s.%N)
  if [ "$name" = remesh ]; then
    regressions="$ROOT/tests/data/fuzz-regressions-remesh"
    # -timeout=30: refinement at 34 degrees can run to its insertion cap (about 3 s natively, over
    # 10 s under the sanitizers: tests/fuzz/README.md); a real hang still stops the run
    "$OUT/bin/fuzz_remesh" -max_total_time="$SECONDS_REMESH" -print_final_stats=1 -max_len=256 -timeout=30 \
      -rss_limit_mb=2048 -artifact_prefix="$art" "$corpus" "$seeds" "$regressions" >"$logf" 2>&1
  else
    "$OUT/bin/fuzz_read_$name" -max_total_time="$SECONDS_EACH" -print_final_stats=1 -dict="$ROOT/tests/fuzz/mesh.dict" \
      -max_len=16384 -timeout=10 -rss_limit_mb=2048 -artifact_prefix="$art" \
      "$corpus" "$seeds" "$regressions" >"$logf" 2>&1
  fi
  rc=$?
  t1=$(date +%s.%N)
  execs=$(grep -o 'stat::number_of_executed_units: [0-9]*' "$logf" | tail -1 | awk '{print $2}')
  [ -z "$execs" ] && execs=$(grep -o '#[0-9]*' "$logf" | tail -1 | tr -d '#')
  [ -z "$execs" ] && execs=0
  secs=$(awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.1f", b - a}')
  ncorpus=$(ls "$corpus" | wc -l)
  result="ok"
  found=()
  for f in "$art"*; do
    [ -f "$f" ] || continue
    base="$(basename "$f")"
    dest="$regressions/$name-$base"
    cp "$f" "$dest"
    found+=("${dest#"$ROOT/"}")
    rm -f "$f"
  done
  if [ $rc -ne 0 ] || [ ${#found[@]} -gt 0 ]; then
    result="FOUND (exit $rc): ${found[*]:-see $logf}"
    failed=1
    grep -m5 -E "ERROR: |runtime error|property violated|SUMMARY" "$logf" | sed 's/^/    /'
  fi
  printf "%-11s %12s %8.1f %10.0f %8s  %s\n" "$name" "$execs" "$secs" "$(awk -v e="$execs" -v s="$secs" 'BEGIN {print (s > 0 ? e / s : 0)}')" "$ncorpus" "$result"
  findings=""
  for x in "${found[@]}"; do findings="$findings${findings:+,}\"$x\""; done
  [ $first -eq 0 ] && echo "," >> "$summary"
  first=0
  printf '{"target":"%s","started":"%s","executions":%s,"seconds":%s,"corpusFiles":%s,"exitCode":%s,"findings":[%s]}' \
    "$name" "$(date -u -d "@${t0%.*}" +%FT%TZ)" "$execs" "$secs" "$ncorpus" "$rc" "$findings" >> "$summary"
done
echo "]}" >> "$summary"
mkdir -p "$ROOT/bench/results"
latest="$ROOT/bench/results/fuzz-latest.json"
if [ -n "$WANT" ] && [ -f "$latest" ]; then
  # a subset run keeps the latest figures of the other targets (each entry has its own "started")
  node -e '
    const fs = require("fs");
    const [now, old] = [process.argv[1], process.argv[2]].map((f) => JSON.parse(fs.readFileSync(f, "utf8")));
    const ran = new Set(now.targets.map((t) => t.target));
    now.targets.push(...old.targets.filter((t) => !ran.has(t.target)).map((t) => ({ started: old.started, ...t })));
    fs.writeFileSync(process.argv[2], JSON.stringify(now) + "\n");
  ' "$summary" "$latest" || cp "$summary" "$latest"
else
  cp "$summary" "$latest"
fi
total=$(grep -o '"executions":[0-9]*' "$summary" | awk -F: '{s+=$2} END {print s+0}')
echo "fuzz: $total executions in total; summary in build/fuzz/summary.json and bench/results/fuzz-latest.json"
exit $failed
