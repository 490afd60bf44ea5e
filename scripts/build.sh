#!/usr/bin/env bash
# Build everything: the native library, tests and CLI (build/native), the WASM module and the
# WASM test suite (build/wasm), and the npm package contents (dist/).
set -euo pipefail
cd "$(dirname "$0")/.."
JOBS="${CONFORMESH_JOBS:-2}"
export NODE_PATH=/usr/share/nodejs

echo "== native build (build/native)"
cmake -S . -B build/native -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/native -j "$JOBS"

echo "== wasm build (build/wasm)"
if [ ! -f build/wasm/CMakeCache.txt ]; then
  emcmake cmake -S . -B build/wasm -G Ninja -DCMAKE_BUILD_TYPE=Release \
    "-DCMAKE_CROSSCOMPILING_EMULATOR=/usr/bin/node;--no-experimental-fetch" >/dev/null
fi
cmake --build build/wasm -j "$JOBS"

echo "== npm package (dist/)"
rm -rf dist && mkdir -p dist
cp build/wasm/conformesh.mjs build/wasm/conformesh.wasm dist/
# the threaded build (cross-origin isolated pages; CONFORMESH_WASM_THREADS=ON by default)
if [ -f build/wasm/conformesh-mt.wasm ]; then
  cp build/wasm/conformesh-mt.mjs build/wasm/conformesh-mt.wasm build/wasm/conformesh-mt.worker.js dist/
fi
if [ -f bindings/tsconfig.json ]; then
  npx tsc -p bindings/tsconfig.json
fi
echo "build done: build/native/conformesh, dist/"
