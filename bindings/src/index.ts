// conformesh — the package entry for Node.js (package.json "exports" condition "node", and
// "main"): the whole API of the browser entry (browser.ts), with the Node platform installed: the
// .wasm is read from disk and createRemesher's workers are worker_threads.
import { setPlatform } from './platform.js';
import { nodePlatform } from './platform-node.js';

setPlatform(nodePlatform);

export * from './browser.js';
