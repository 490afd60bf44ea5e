// Worker entry for Node.js (worker_threads): the same handler as the module Web Worker.
// createRemesher uses it by default in Node; browsers use worker.js.
import { parentPort } from 'node:worker_threads';
import { setPlatform } from './platform.js';
import { nodePlatform } from './platform-node.js';
import type { WorkerRequest } from './protocol.js';
import { createWorkerHandler } from './worker.js';

setPlatform(nodePlatform);

const port = parentPort;
if (port) {
  const handle = createWorkerHandler();
  port.on('message', (request: WorkerRequest) => {
    void handle(request, (message, transfer) => port.postMessage(message, transfer as never));
  });
}
