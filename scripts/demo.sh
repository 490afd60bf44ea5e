#!/usr/bin/env bash
# Build the library (dist/) and the demo page (web/dist/), then serve the page on localhost and
# print its URL once the server answers. PORT=… to choose the port (default 5173); --no-build to
# serve the last build.
set -euo pipefail
cd "$(dirname "$0")/.."
PORT="${PORT:-5173}"
if [ "${1:-}" != "--no-build" ]; then
  bash scripts/ensure-deps.sh
  bash scripts/build.sh
  npx vite build --config web/vite.config.ts --logLevel warn
fi
URL="http://127.0.0.1:${PORT}/"
npx vite preview --config web/vite.config.ts --port "$PORT" --strictPort --logLevel warn &
server=$!
trap 'kill "$server" 2>/dev/null || true' EXIT INT TERM
# the URL once the server answers (not before: a browser opened on it early gets an error page)
for _ in $(seq 1 300); do
  if curl -fs -o /dev/null "$URL"; then
    echo ""
    echo "conformesh demo page: $URL   (Ctrl+C to stop)"
    echo ""
    break
  fi
  if ! kill -0 "$server" 2>/dev/null; then
    echo "demo: the page server exited (port $PORT taken? PORT=... to choose another)" >&2
    wait "$server"
    exit 1
  fi
  sleep 0.1
done
wait "$server"
