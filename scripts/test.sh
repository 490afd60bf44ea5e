#!/usr/bin/env bash
# Run every test: native doctest (+ ASan/UBSan corpus) via CTest, the WASM doctest suite under
# Node via CTest, then Vitest (JS API, package, and the page in headless Chromium).
set -euo pipefail
cd "$(dirname "$0")/.."

echo "== native tests (ctest)"
ctest --test-dir build/native --output-on-failure
echo "== wasm tests (ctest, node)"
ctest --test-dir build/wasm --output-on-failure
echo "== js tests (vitest)"
npx vitest run tests/js
# The page tests measure the main thread's frame gaps during a remesh: they run after the others,
# one file at a time, so the measurement does not share the two cores with other CPU-heavy tests.
echo "== page tests (vitest, headless Chromium)"
npx vitest run tests/e2e --no-file-parallelism
