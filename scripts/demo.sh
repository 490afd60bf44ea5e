#!/usr/bin/env bash
# Build the library (dist/) and the demo page (web/dist/), then serve the page on localhost and
# print its URL. PORT=… to choose the port (default 5173); --no-build to serve the last build.
set -euo pipefail
cd "$(dirname "$0")/.."
PORT="${PORT:-5173}"
if [ "${1:-}" != "--no-build" ]; then
  bash scripts/ensure-deps.sh
  bash scripts/build.sh
  npx vite build --config web/vite.config.ts --logLevel warn
fi
echo ""
echo "conformesh demo page: http://127.0.0.1:${PORT}/   (Ctrl+C to stop)"
echo ""
exec npx vite preview --config web/vite.config.ts --port "$PORT" --strictPort
