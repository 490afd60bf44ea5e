// Where the package meets its host: reading the .wasm file and starting a worker.
//
// The browser entry (browser.ts, package.json "exports" default condition) reaches only this
// module, whose implementation uses web APIs alone (fetch, module Web Workers). The Node entry
// (index.ts, "node" condition) and Node's worker script install platform-node.ts, which uses
// node:fs and node:worker_threads. No module the browser entry imports names a Node builtin, so a
// bundler builds a web app without "externalized for browser compatibility" warnings
// (tests/js/vite-consumer.test.ts).
import type { WorkerLike } from './remesher.js';

export interface Platform {
  /** 'node': Node.js (files read from disk, worker_threads); 'web': browsers and Web Workers. */
  readonly name: 'node' | 'web';
  /** The bytes of a local (file:) URL; absent where there is no file system (the .wasm is fetched). */
  readFile?: (url: URL) => Promise<Uint8Array>;
  /** Start a worker that runs this package's worker handler (createRemesher's default). */
  createWorker(): WorkerLike | Promise<WorkerLike>;
}

const web: Platform = {
  name: 'web',
  // a literal `new URL('./worker.js', import.meta.url)`: bundlers (Vite) find and bundle the worker
  createWorker: () => new Worker(new URL('./worker.js', import.meta.url), { type: 'module' }),
};

let current: Platform = web;

/** The host platform: the web one unless an entry installed another (index.ts in Node). */
export function platform(): Platform {
  return current;
}

/** Install the host platform (the Node entry and the Node worker script do, on import). */
export function setPlatform(p: Platform): void {
  current = p;
}
