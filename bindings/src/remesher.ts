// createRemesher: the API running in workers (module Web Workers in browsers, worker_threads in
// Node), so long calls never block the page. Protocol: protocol.ts.
import { threadsFor, wasmLocation } from './loader.js';
import { platform } from './platform.js';
import type { CallRequest, WorkerMethod, WorkerRequest, WorkerResponse } from './protocol.js';
import { transferablesOf } from './protocol.js';
import { METHOD_NAMES, METHODS, sendArgs, type MethodName, type WorkerMethods } from './methods.js';
import type { StageName } from './stages.js';
import { ConformeshError, invalidArgument } from './status.js';

/** A progress report: stage and fraction in [0, 1], monotone within a call, ending at 1. */
export interface ProgressEvent {
  stage: StageName;
  fraction: number;
}

/** Per-call options of the worker API. */
export interface CallOptions {
  /** Aborting rejects the call with ConformeshError 'Cancelled' (a running call's worker is terminated). */
  signal?: AbortSignal;
  onProgress?: (event: ProgressEvent) => void;
  /**
   * Transfer the input arrays' buffers to the worker instead of copying them (faster for big
   * meshes; the caller's arrays become empty). Default false.
   */
  transfer?: boolean;
}

/** Something that behaves like a Worker: a Web Worker or Node's worker_threads Worker. */
export interface WorkerLike {
  postMessage(message: unknown, transfer?: Transferable[]): void;
  terminate(): unknown;
  addEventListener?(type: 'message' | 'error', listener: (ev: { data?: unknown; message?: string }) => void): void;
  on?(type: 'message' | 'error' | 'exit', listener: (value: unknown) => void): void;
  /** Node worker_threads: an idle worker is unref'd so it does not keep the process alive. */
  ref?(): void;
  unref?(): void;
}

export interface RemesherOptions {
  /** Number of workers (default 1). Calls are spread over idle workers. */
  workers?: number;
  /**
   * Create a worker. Default (platform.ts): `new Worker(new URL('./worker.js', import.meta.url),
   * {type: 'module'})` in browsers, a worker_threads Worker running node-worker.js in Node.
   */
  createWorker?: () => WorkerLike | Promise<WorkerLike>;
  /**
   * Passed to each worker's module loader (e.g. a compiled WebAssembly.Module to skip compiling;
   * `threads`: InitOptions.threads, the threads of each worker's calls).
   */
  init?: { wasmModule?: WebAssembly.Module; wasmBinary?: ArrayBuffer | Uint8Array; wasmUrl?: string; threads?: number };
}

/**
 * The package API, asynchronous, running in workers. terminate() stops them (in Node, idle
 * workers do not keep the process alive; in browsers they live until terminate() or page unload).
 */
export interface Remesher extends WorkerMethods<CallOptions> {
  readonly workers: number;
  version(): Promise<string>;
  /** Threads a call runs on in a worker (above 1 with the threaded build: cross-origin isolated pages). */
  threads(): Promise<number>;
  /** Stop every worker; pending calls reject with 'Cancelled'. */
  terminate(): void;
}


interface Job {
  id: number;
  method: WorkerMethod;
  args: unknown[];
  transfer: Transferable[];
  options: CallOptions;
  resolve: (value: unknown) => void;
  reject: (error: unknown) => void;
  onAbort?: () => void;
}

interface Slot {
  worker: Promise<WorkerLike> | undefined;
  job: Job | undefined;
}

function cancelled(): ConformeshError {
  return new ConformeshError('Cancelled', 'api', 'the call was cancelled');
}

/** Start a pool of workers serving the API. */
export function createRemesher(options: RemesherOptions = {}): Remesher {
  const count = options.workers ?? 1;
  if (!Number.isInteger(count) || count < 1 || count > 64) throw invalidArgument('workers must be an integer in [1, 64]');
  const create = options.createWorker ?? (() => platform().createWorker());
  const slots: Slot[] = Array.from({ length: count }, () => ({ worker: undefined, job: undefined }));
  const queue: Job[] = [];
  let nextId = 1;
  let terminated = false;

  const finish = (slot: Slot, job: Job) => {
    if (job.onAbort) job.options.signal?.removeEventListener('abort', job.onAbort);
    if (slot.job === job) {
      slot.job = undefined;
      void slot.worker?.then((x) => x.unref?.(), () => {});
    }
    pump();
  };

  const kill = (slot: Slot) => {
    const w = slot.worker;
    slot.worker = undefined;
    void w?.then((x) => x.terminate(), () => {});
  };

  const onMessage = (slot: Slot, data: unknown) => {
    const msg = data as WorkerResponse;
    const job = slot.job;
    if (!job || msg.id !== job.id) return;
    if (msg.type === 'progress') {
      try {
        job.options.onProgress?.({ stage: msg.stage, fraction: msg.fraction });
      } catch {
        // a throwing progress listener must not break the pool
      }
    } else if (msg.type === 'result') {
      finish(slot, job);
      job.resolve(msg.value);
    } else if (msg.type === 'error') {
      finish(slot, job);
      job.reject(ConformeshError.fromData(msg.error));
    }
  };

  const onFailure = (slot: Slot, what: unknown) => {
    const job = slot.job;
    kill(slot);
    if (job) {
      finish(slot, job);
      const message = (what as { message?: string })?.message ?? String(what);
      job.reject(new ConformeshError('InternalError', 'api', `worker failed: ${message}`));
    }
  };

  // Browsers: compile the module once, off the main thread (compileStreaming), and give every
  // worker the compiled module, replacements after a cancel included: a worker that compiled
  // its own copy kept the cores busy for a second right when the next call started, and the
  // page's frames stalled. Skipped when the caller passes its own module or bytes, and in Node
  // (each worker reads the file); any failure falls back to the worker loading it itself.
  let shared: Promise<RemesherOptions['init']> | undefined;
  const initFor = (): Promise<RemesherOptions['init']> => {
    const given = options.init ?? {};
    if (given.wasmModule || given.wasmBinary || platform().name === 'node' || typeof WebAssembly === 'undefined' || typeof fetch !== 'function')
      return Promise.resolve(given);
    shared ??= (async () => {
      // the build the workers load (they are as cross-origin isolated as this page)
      const threads = threadsFor(given);
      const url = given.wasmUrl ?? wasmLocation(threads > 1);
      try {
        const response = await fetch(url);
        if (!response.ok) return given;
        const wasmModule =
          typeof WebAssembly.compileStreaming === 'function' && (response.headers.get('content-type') ?? '').startsWith('application/wasm')
            ? await WebAssembly.compileStreaming(response)
            : await WebAssembly.compile(await response.arrayBuffer());
        return { ...given, wasmModule, threads };
      } catch {
        return given;
      }
    })();
    return shared;
  };

  const startWorker = (slot: Slot): Promise<WorkerLike> => {
    // the listeners go on at once (a worker script that fails to load reports it right away);
    // the init message waits for the shared compiled module
    const w = Promise.resolve().then(create).then(async (worker) => {
      if (worker.addEventListener) {
        worker.addEventListener('message', (ev) => onMessage(slot, ev.data));
        worker.addEventListener('error', (ev) => onFailure(slot, ev));
      } else if (worker.on) {
        worker.on('message', (value) => onMessage(slot, value));
        worker.on('error', (err) => onFailure(slot, err));
        worker.on('exit', (code) => {
          if (slot.worker === w) onFailure(slot, new Error(`the worker exited (code ${String(code)})`));
        });
        worker.unref?.();
      } else {
        throw new Error('createWorker returned an object without addEventListener or on');
      }
      // load and compile the module now, not inside the first call (keeps a replacement worker's
      // start-up out of the next call after a cancel, and off the main thread's frames then)
      const init = await initFor();
      worker.postMessage({ id: 0, type: 'init', options: init ?? {} } satisfies WorkerRequest);
      return worker;
    });
    return w;
  };

  const pump = () => {
    for (const slot of slots) {
      if (terminated || queue.length === 0) return;
      if (slot.job) continue;
      const job = queue.shift()!;
      slot.job = job;
      slot.worker ??= startWorker(slot);
      slot.worker.then(
        (worker) => {
          if (slot.job !== job) return;
          const request: CallRequest = { id: job.id, type: 'call', method: job.method, args: job.args };
          worker.ref?.();
          try {
            worker.postMessage(request, job.transfer);
          } catch (e) {
            // e.g. an argument that cannot be cloned
            finish(slot, job);
            job.reject(new ConformeshError('InvalidArgument', 'api', `cannot send the call to the worker: ${(e as Error).message}`));
          }
        },
        (e: unknown) => onFailure(slot, e),
      );
    }
  };

  const submit = (method: WorkerMethod, args: unknown[], call: CallOptions = {}): Promise<unknown> => {
    if (terminated) return Promise.reject(new ConformeshError('Cancelled', 'api', 'the remesher was terminated'));
    if (call.signal?.aborted) return Promise.reject(cancelled());
    return new Promise((resolve, reject) => {
      const job: Job = {
        id: nextId++,
        method,
        args,
        transfer: call.transfer ? transferablesOf(args) : [],
        options: call,
        resolve,
        reject,
      };
      if (call.signal) {
        job.onAbort = () => {
          const queued = queue.indexOf(job);
          if (queued >= 0) {
            queue.splice(queued, 1);
          } else {
            const slot = slots.find((s) => s.job === job);
            if (!slot) return;
            kill(slot); // the WASM call cannot be interrupted: drop the worker and start a fresh one now
            slot.job = undefined;
            if (!terminated) slot.worker = startWorker(slot);
          }
          call.signal!.removeEventListener('abort', job.onAbort!);
          reject(cancelled());
          pump();
        };
        call.signal.addEventListener('abort', job.onAbort);
      }
      queue.push(job);
      pump();
    });
  };

  // each method of the table: its arguments checked and copied here, the call options last
  const methods = {} as Record<MethodName, (...args: unknown[]) => Promise<unknown>>;
  for (const name of METHOD_NAMES) {
    const arity = METHODS[name].send.length;
    methods[name] = async (...args) => submit(name, sendArgs(name, args), args[arity] as CallOptions | undefined);
  }

  return {
    workers: count,
    ...(methods as WorkerMethods<CallOptions>),
    version: async () => (await submit('version', [])) as string,
    threads: async () => (await submit('threads', [])) as number,
    terminate: () => {
      if (terminated) return;
      terminated = true;
      for (const job of queue.splice(0)) job.reject(new ConformeshError('Cancelled', 'api', 'the remesher was terminated'));
      for (const slot of slots) {
        const job = slot.job;
        kill(slot);
        if (job) {
          finish(slot, job);
          job.reject(new ConformeshError('Cancelled', 'api', 'the remesher was terminated'));
        }
      }
    },
  };
}
