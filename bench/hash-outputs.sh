#!/bin/bash
# Hash the remeshed output of every model of ../shared/data at the defaults, and fandisk at
# 0.004, with the CLI given (default: build/native/conformesh). A structural change keeps the
# outputs byte-identical: run it before and after and `diff` the two listings.
#   bash bench/hash-outputs.sh [BIN] > hashes.txt
# EXTRA: more flags for every run, left out of the listing (EXTRA='--threads 2': the same listing
# as '--threads 1' when the output does not depend on the thread count).
set -u
EXTRA="${EXTRA:-}"
HERE="$(cd "$(dirname "$0")/.." && pwd)"
BIN="${1:-$HERE/build/native/conformesh}"
DATA="${DATA:-$HERE/../shared/data}"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
run() {  # name, input, flags...
  local name="$1" input="$2"
  shift 2
  if "$BIN" remesh "$input" -o "$TMP/out.obj" --no-hausdorff "$@" ${EXTRA:-} > /dev/null 2> "$TMP/err"; then
    echo "$(sha256sum < "$TMP/out.obj" | cut -c1-16)  $name $*"
  else
    echo "exit $?: $(head -c 120 "$TMP/err" | tr '\n' ' ')  $name $*"
  fi
}
for f in "$DATA"/*.off "$DATA"/*.obj "$DATA"/*.stl; do
  run "$(basename "$f")" "$f"
done
run fandisk.off "$DATA/fandisk.off" --edge-length-rel 0.004
