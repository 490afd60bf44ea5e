// Vite config of the demo page. The page imports the package exactly as a user would
// ('conformesh', 'conformesh/three'); here those names resolve to the repository's built package
// in ../dist (scripts/build.sh), so the page always runs the library built from this tree:
// 'conformesh' to its browser entry, as package.json "exports" resolves it for a browser build.
import { fileURLToPath } from 'node:url';
import { defineConfig } from 'vite';

const dist = fileURLToPath(new URL('../dist/', import.meta.url));
// Cross-origin isolation: with these headers the library runs a remesh on every core (its
// threaded build needs SharedArrayBuffer); without them, on one. A site serving the built page
// sends the same two headers.
const isolation = { 'Cross-Origin-Opener-Policy': 'same-origin', 'Cross-Origin-Embedder-Policy': 'require-corp' };

export default defineConfig({
  root: fileURLToPath(new URL('.', import.meta.url)),
  base: './',
  resolve: {
    alias: [
      { find: /^conformesh\/three$/, replacement: `${dist}three.js` },
      { find: /^conformesh$/, replacement: `${dist}browser.js` },
    ],
  },
  worker: { format: 'es' },
  build: {
    outDir: 'dist',
    emptyOutDir: true,
    target: 'es2022',
    chunkSizeWarningLimit: 1500,
  },
  server: { host: '127.0.0.1', headers: isolation },
  preview: { host: '127.0.0.1', headers: isolation },
});
