// The Node.js platform (see platform.ts): the .wasm read from disk, workers on worker_threads.
// Imported only by the Node entry (index.ts), the Node worker script and the CLI.
import { readFile } from 'node:fs/promises';
import { Worker } from 'node:worker_threads';
import type { Platform } from './platform.js';
import type { WorkerLike } from './remesher.js';

export const nodePlatform: Platform = {
  name: 'node',
  readFile: async (url) => readFile(url),
  createWorker: () => {
    // Workers inherit the parent's execArgv; --input-type (node -e scripts) is an error there.
    const execArgv = process.execArgv.filter((a) => !a.startsWith('--input-type'));
    return new Worker(new URL('./node-worker.js', import.meta.url), { execArgv }) as unknown as WorkerLike;
  },
};
