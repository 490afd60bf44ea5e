#!/usr/bin/env bash
# npm run bench — benchmarks with peers, measured side by side in the same run.
#
#   bash bench/run.sh [--sections io,2d,flatten,remesh,wasm,page,scaling] [--quick] [--repeat N]
#
# 1. installs the peers' Debian packages when missing (CGAL: libcgal-dev; gmsh),
# 2. builds the peer drivers (bench/peers/*.cpp: our code calling the peer libraries) and the
#    process meter (bench/tools/runstat.c) into bench/work/peers/,
# 3. builds our native tools if needed (build/native: quality_tool, bench_prep, the CLI),
# 4. runs bench/run.mjs: each section independent; a failing or missing tool is reported, never
#    fatal; tables of ratios on stdout, JSON and Markdown under bench/results/.
set -uo pipefail
cd "$(dirname "$0")/.."
ROOT="$(pwd)"
WORK="$ROOT/bench/work"
PEERS_BIN="$WORK/peers"
mkdir -p "$PEERS_BIN" "$ROOT/bench/results"

# ---- 1. peers' Debian packages ----------------------------------------------------------------
need=()
for pkg in libcgal-dev libgmp-dev libmpfr-dev gmsh; do
  dpkg -s "$pkg" >/dev/null 2>&1 || need+=("$pkg")
done
if [ ${#need[@]} -gt 0 ]; then
  echo "bench: installing peer packages: ${need[*]} (CGAL headers, gmsh; a minute or two)"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -q || echo "bench: apt-get update failed (continuing)"
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${need[@]}" \
    || echo "bench: WARNING: could not install ${need[*]}; the peer sections will report it"
fi

# ---- 2. peer drivers --------------------------------------------------------------------------
# Rebuilt when the source (or the shared header) is newer than the binary.
build_peer() {  # name, extra flags...
  local name="$1"
  shift
  local src="$ROOT/bench/peers/$name.cpp" bin="$PEERS_BIN/$name"
  if [ -x "$bin" ] && [ "$bin" -nt "$src" ] && [ "$bin" -nt "$ROOT/bench/peers/peer_util.h" ]; then return 0; fi
  echo "bench: building peer driver $name"
  g++ -std=c++17 -O2 -DNDEBUG -DCGAL_NDEBUG "$@" -o "$bin" "$src" -lgmp -lmpfr \
    || { echo "bench: WARNING: peer driver $name did not build"; rm -f "$bin"; }
}
if [ -f /usr/include/CGAL/version.h ]; then
  build_peer cgal_mesh2
  build_peer cgal_remesh
  build_peer cgal_dcm -DCGAL_EIGEN3_ENABLED -I/usr/include/eigen3
else
  echo "bench: CGAL headers missing: CGAL sections will report it"
fi
if [ ! -x "$PEERS_BIN/runstat" ] || [ "$ROOT/bench/tools/runstat.c" -nt "$PEERS_BIN/runstat" ]; then
  gcc -O2 -o "$PEERS_BIN/runstat" "$ROOT/bench/tools/runstat.c" || { echo "bench: runstat did not build"; exit 1; }
fi

# ---- 3. our native tools ----------------------------------------------------------------------
if [ ! -x build/native/quality_tool ] || [ ! -x build/native/bench_prep ]; then
  echo "bench: building native tools (build/native)"
  cmake -S . -B build/native -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null && \
    cmake --build build/native -j "${CONFORMESH_JOBS:-2}" || echo "bench: WARNING: native build failed"
fi

# ---- 4. sections ------------------------------------------------------------------------------
exec node "$ROOT/bench/run.mjs" "$@"
