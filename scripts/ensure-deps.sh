#!/usr/bin/env bash
# Install what conformesh needs to build and test, skipping what is already there.
# Debian 12 packages (as root, non-interactive) and the npm devDependencies (npm ci).
set -euo pipefail
cd "$(dirname "$0")/.."

need=()
command -v cmake >/dev/null 2>&1 || need+=(cmake)
command -v ninja >/dev/null 2>&1 || need+=(ninja-build)
command -v g++ >/dev/null 2>&1 || need+=(g++)
command -v em++ >/dev/null 2>&1 || need+=(emscripten)
command -v wasm-opt >/dev/null 2>&1 || need+=(binaryen)
[ -f /usr/include/eigen3/Eigen/Sparse ] || need+=(libeigen3-dev)
[ -f /usr/include/doctest/doctest.h ] || need+=(doctest-dev)
command -v chromium >/dev/null 2>&1 || need+=(chromium)
# ASan/UBSan runtime for the sanitizer test binary (g++ ships it with libasan/libubsan).
dpkg -s libasan8 >/dev/null 2>&1 || need+=(libasan8)
dpkg -s libubsan1 >/dev/null 2>&1 || need+=(libubsan1)

if [ ${#need[@]} -gt 0 ]; then
  echo "conformesh: installing Debian packages: ${need[*]} (this takes a few minutes on a new machine)"
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q "${need[@]}"
fi

# npm devDependencies: reinstall when node_modules is missing or older than the lock file.
stamp=node_modules/.conformesh-lock-stamp
if [ ! -f "$stamp" ] || ! cmp -s package-lock.json "$stamp"; then
  echo "conformesh: installing npm packages (npm ci)"
  npm ci --no-audit --no-fund
  cp package-lock.json "$stamp"
fi
