// Messages between the Remesher client (remesher.ts) and a worker (worker.ts).
//   client -> worker  { id, type: 'init', options }            optional, before any call
//                     { id, type: 'call', method, args }
//   worker -> client  { id, type: 'progress', stage, fraction }  zero or more, fraction monotone
//                     { id, type: 'result', value }              typed arrays transferred
//                     { id, type: 'error', error }               ConformeshErrorData
// One call is in flight per worker at a time; cancel = terminate that worker (a running WASM
// call cannot see messages), and the client starts a fresh one for the next call.
import type { MethodName } from './methods.js';
import type { StageName } from './stages.js';
import type { ConformeshErrorData } from './status.js';

/** Methods a worker serves: the table's (methods.ts), and the module's version and threads. */
export type WorkerMethod = MethodName | 'version' | 'threads';

export interface InitRequest {
  id: number;
  type: 'init';
  options: { wasmModule?: WebAssembly.Module; wasmBinary?: ArrayBuffer | Uint8Array; wasmUrl?: string; threads?: number };
}

export interface CallRequest {
  id: number;
  type: 'call';
  method: WorkerMethod;
  args: unknown[];
}

export type WorkerRequest = InitRequest | CallRequest;

export interface ProgressMessage {
  id: number;
  type: 'progress';
  stage: StageName;
  fraction: number;
}

export interface ResultMessage {
  id: number;
  type: 'result';
  value: unknown;
}

export interface ErrorMessage {
  id: number;
  type: 'error';
  error: ConformeshErrorData;
}

export type WorkerResponse = ProgressMessage | ResultMessage | ErrorMessage;

/** Post a message with a transfer list (Worker.postMessage, MessagePort, worker_threads). */
export type PostFn = (message: WorkerResponse, transfer: Transferable[]) => void;

/** The ArrayBuffers under the typed arrays of a value (1 level of objects/arrays deep), once each. */
export function transferablesOf(value: unknown): ArrayBuffer[] {
  const out = new Set<ArrayBuffer>();
  const visit = (v: unknown, depth: number) => {
    if (ArrayBuffer.isView(v)) {
      if (v.buffer instanceof ArrayBuffer) out.add(v.buffer);
    } else if (v instanceof ArrayBuffer) {
      out.add(v);
    } else if (depth < 4 && typeof v === 'object' && v !== null) {
      for (const x of Array.isArray(v) ? v : Object.values(v)) visit(x, depth + 1);
    }
  };
  visit(value, 0);
  return [...out];
}
