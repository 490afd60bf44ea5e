// The worker side of createRemesher. `createWorkerHandler()` is a plain function so it can be
// tested without a worker (and wired to any message channel: a module Web Worker below, Node's
// worker_threads in node-worker.ts). Loaded as a module Web Worker it installs itself.
import { bindApi, type Conformesh } from './api.js';
import { loadRaw, type InitOptions } from './loader.js';
import type { CallRequest, PostFn, WorkerMethod, WorkerRequest } from './protocol.js';
import { transferablesOf } from './protocol.js';
import type { StageName } from './stages.js';
import { ConformeshError, type ConformeshErrorData } from './status.js';
import type { MeshFormat, MeshInfo, ReadMeshResult } from './types.js';

type MethodImpl = (api: Conformesh, args: unknown[], progress: (stage: StageName, fraction: number) => void) => unknown;

/**
 * Each method: how a request's args map onto the synchronous API. Adding an API function to the
 * worker is one entry here plus one method in remesher.ts (docs/BINDINGS.md).
 */
const methods: Record<WorkerMethod, MethodImpl> = {
  readMesh: (api, [bytes, format], progress) => {
    const r: ReadMeshResult = api.readMesh(bytes as Uint8Array, format as MeshFormat);
    progress('read', 1);
    return r;
  },
  writeMesh: (api, [mesh, format, options], progress) => {
    const r = api.writeMesh(mesh as never, format as MeshFormat, options as never);
    progress('write', 1);
    return r;
  },
  meshInfo: (api, [mesh, options], progress) => {
    const r: MeshInfo = api.meshInfo(mesh as never, options as never);
    progress('validate', 1);
    return r;
  },
  validateMesh: (api, [mesh, options], progress) => {
    const r = api.validateMesh(mesh as never, options as never);
    progress('validate', 1);
    return r;
  },
  refine2d: (api, [pslg, options], progress) => {
    const r = api.refine2d(pslg as never, options as never, { onProgress: (e) => progress(e.stage, e.fraction) });
    progress('refine', 1);
    return r;
  },
  readPoly: (api, [bytes], progress) => {
    const r = api.readPoly(bytes as Uint8Array);
    progress('read', 1);
    return r;
  },
  flatten: (api, [mesh, options], progress) => {
    const r = api.flatten(mesh as never, options as never, { onProgress: (e) => progress(e.stage, e.fraction) });
    progress('flatten', 1);
    return r;
  },
  remesh: (api, [mesh, options], progress) => {
    let stage: StageName = 'api';
    const r = api.remesh(mesh as never, options as never, {
      onProgress: (e) => {
        stage = e.stage;
        progress(e.stage, e.fraction);
      },
    });
    progress(stage, 1);
    return r;
  },
  version: (api) => api.version,
  threads: (api) => api.threads,
};

function errorData(e: unknown): ConformeshErrorData {
  if (e instanceof ConformeshError) return e.result ? { ...e.toJSON(), result: e.result } : e.toJSON();
  const message = e instanceof Error ? e.message : String(e);
  return new ConformeshError('InternalError', 'api', `worker: ${message}`).toJSON();
}

/**
 * A message handler: `handle(request, post)` answers one request by calling `post` (progress
 * messages, then exactly one result or error). Resolves when the answer has been posted.
 */
export function createWorkerHandler(): (request: WorkerRequest, post: PostFn) => Promise<void> {
  let initOptions: InitOptions = {};
  let api: Promise<Conformesh> | undefined;
  const getApi = () =>
    (api ??= loadRaw(initOptions).then(bindApi, (e: unknown) => {
      api = undefined;
      throw e;
    }));

  return async (request, post) => {
    const id = typeof request?.id === 'number' ? request.id : -1;
    try {
      if (request?.type === 'init') {
        initOptions = { ...request.options };
        await getApi();
        post({ id, type: 'result', value: null }, []);
        return;
      }
      if (request?.type !== 'call') throw new ConformeshError('InvalidArgument', 'api', 'worker: unknown message type');
      const call = request as CallRequest;
      const impl = Object.prototype.hasOwnProperty.call(methods, call.method) ? methods[call.method] : undefined;
      if (!impl) throw new ConformeshError('InvalidArgument', 'api', `worker: unknown method '${String(call.method)}'`);
      const args = Array.isArray(call.args) ? call.args : [];
      let last = -1;
      const progress = (stage: StageName, fraction: number) => {
        const f = Math.min(1, Math.max(last, fraction));
        if (f === last) return;
        last = f;
        post({ id, type: 'progress', stage, fraction: f }, []);
      };
      const value = impl(await getApi(), args, progress);
      post({ id, type: 'result', value }, transferablesOf(value));
    } catch (e) {
      const error = errorData(e);
      post({ id, type: 'error', error }, transferablesOf(error.result));
    }
  };
}

interface WorkerScope {
  onmessage: ((ev: MessageEvent) => void) | null;
  postMessage(message: unknown, transfer: Transferable[]): void;
}

// Running as a module Web Worker: answer messages from the page.
declare const WorkerGlobalScope: (abstract new () => unknown) | undefined;
if (typeof WorkerGlobalScope !== 'undefined' && globalThis instanceof WorkerGlobalScope) {
  const scope = globalThis as unknown as WorkerScope;
  const handle = createWorkerHandler();
  scope.onmessage = (ev) => {
    void handle(ev.data as WorkerRequest, (message, transfer) => scope.postMessage(message, transfer));
  };
}
