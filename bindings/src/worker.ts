// The worker side of createRemesher. `createWorkerHandler()` is a plain function so it can be
// tested without a worker (and wired to any message channel: a module Web Worker below, Node's
// worker_threads in node-worker.ts). Loaded as a module Web Worker it installs itself.
import { bindApi, type Conformesh } from './api.js';
import { loadRaw, type InitOptions } from './loader.js';
import type { CallRequest, PostFn, WorkerMethod, WorkerRequest } from './protocol.js';
import { transferablesOf } from './protocol.js';
import type { StageName } from './stages.js';
import { ConformeshError, type ConformeshErrorData } from './status.js';
import { METHOD_NAMES, METHODS, type MethodName } from './methods.js';

type MethodImpl = (api: Conformesh, args: unknown[], progress: (stage: StageName, fraction: number) => void) => unknown;

/**
 * A table method's call: its arguments (the row's arity), progress relayed when the row takes it,
 * and a last report at 1 naming the stage of the last report made (else the row's stage).
 */
function tableMethod(name: MethodName): MethodImpl {
  const row = METHODS[name];
  const arity = row.send.length;
  return (api, args, progress) => {
    let stage: StageName = row.stage;
    const call = row.progress
      ? {
          onProgress: (e: { stage: StageName; fraction: number }) => {
            stage = e.stage;
            progress(e.stage, e.fraction);
          },
        }
      : undefined;
    const fn = api[name] as (...a: unknown[]) => unknown;
    const r = fn(...args.slice(0, arity), call);
    progress(stage, 1);
    return r;
  };
}

/** What a worker serves: every method of the table, and the module's version and threads. */
const methods: Record<WorkerMethod, MethodImpl> = {
  ...(Object.fromEntries(METHOD_NAMES.map((name) => [name, tableMethod(name)])) as Record<MethodName, MethodImpl>),
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
