// Loading the WebAssembly module, once, in any environment: Node 20 (ESM), Vitest, Vite dev and
// build, a plain <script type=module> page, a module Web Worker.
//
// The glue is built with -sENVIRONMENT=web,worker (TOOLCHAIN.md: a `node` environment breaks ES
// module loading), so:
//   * in Node we read the .wasm bytes ourselves, with the Node platform's readFile (installed by
//     the Node entry, platform-node.ts; this file names no Node builtin);
//   * elsewhere we instantiate from `new URL('./conformesh.wasm', import.meta.url)` ourselves
//     (streaming when the server sends application/wasm, else from bytes): the glue's own fetch
//     path has no fallback inside a *module* worker, where `importScripts` is undefined.
//
// Two builds: conformesh.wasm (one thread) and conformesh-mt.wasm (WebAssembly threads: a pool of
// pthread workers started with the module, so one call runs on several cores). The threaded one
// needs SharedArrayBuffer, which browsers give only to cross-origin isolated pages (COOP
// same-origin + COEP require-corp); it is picked there and nowhere else (Node keeps the
// single-threaded build: its glue is built for web and worker only). Both give the same bytes.
import createConformeshModule from './conformesh.mjs';
import { platform } from './platform.js';
import type { RawFactory, RawModule, RawModuleOptions } from './raw.js';
import { ConformeshError } from './status.js';

export interface InitOptions {
  /** The .wasm bytes (skips fetching / reading the file). */
  wasmBinary?: ArrayBuffer | Uint8Array;
  /** A compiled module (e.g. posted from the main thread to a worker). */
  wasmModule?: WebAssembly.Module;
  /** Where to fetch the .wasm from (default: next to this file). */
  wasmUrl?: string | URL;
  /**
   * Threads one call may run on: above 1 loads the threaded build (conformesh-mt.wasm; the
   * wasm options above must then be that build's), 1 the single-threaded one. Default: the
   * hardware's concurrency where threads are available (threadsAvailable()) and no wasm option
   * is given, else 1. Where threads are not available it is 1 whatever is asked.
   */
  threads?: number;
}

/** Whether the threaded build can run here: a browser page or worker that is cross-origin isolated. */
export function threadsAvailable(): boolean {
  const g = globalThis as { crossOriginIsolated?: boolean; SharedArrayBuffer?: unknown; Worker?: unknown };
  return !isNode() && g.crossOriginIsolated === true && typeof g.SharedArrayBuffer === 'function' && typeof g.Worker === 'function';
}

/** The threads a module loaded with `options` runs a call on (1: the single-threaded build). */
export function threadsFor(options: InitOptions): number {
  if (!threadsAvailable()) return 1;
  if (options.threads !== undefined) return Math.max(1, Math.min(64, Math.floor(options.threads) || 1));
  if (options.wasmBinary || options.wasmModule || options.wasmUrl !== undefined) return 1;
  const cores = (globalThis as { navigator?: { hardwareConcurrency?: number } }).navigator?.hardwareConcurrency ?? 1;
  return Math.max(1, Math.min(64, cores));
}

/** True in Node.js (not in browsers, workers or bundles that polyfill `process`). */
export function isNode(): boolean {
  const p = (globalThis as { process?: { versions?: { node?: string }; release?: { name?: string } } }).process;
  return typeof p?.versions?.node === 'string' && p.release?.name === 'node';
}

/** The .wasm file next to the package's scripts (`threaded`: conformesh-mt.wasm). */
export function wasmLocation(threaded = false): URL {
  // literal `new URL(...)` expressions: bundlers find and emit the files
  return threaded ? new URL('./conformesh-mt.wasm', import.meta.url) : new URL('./conformesh.wasm', import.meta.url);
}

async function instantiateFromUrl(url: URL | string, imports: WebAssembly.Imports): Promise<WebAssembly.WebAssemblyInstantiatedSource> {
  const response = await fetch(url, { credentials: 'same-origin' });
  if (!response.ok) throw new Error(`cannot fetch ${String(url)}: HTTP ${response.status}`);
  const type = response.headers.get('content-type') ?? '';
  if (typeof WebAssembly.instantiateStreaming === 'function' && type.startsWith('application/wasm')) {
    return WebAssembly.instantiateStreaming(response, imports);
  }
  return WebAssembly.instantiate(await response.arrayBuffer(), imports);
}

/**
 * The threaded build's factory and options: a pool of `threads - 1` pthread workers (the calling
 * thread is the last one), each loading the glue from its own URL (a bundler renames the files,
 * so the glue cannot find them by its own name).
 */
async function threadedFactory(threads: number, moduleOptions: RawModuleOptions): Promise<RawFactory> {
  const glue = new URL('./conformesh-mt.mjs', import.meta.url).href;
  const pthreadWorker = new URL('./conformesh-mt.worker.js', import.meta.url).href;
  moduleOptions.pthreadPoolSize = threads - 1;
  moduleOptions.mainScriptUrlOrBlob = glue;
  // The pthread workers start from a blob: a bundler may inline the small worker script as a data:
  // URL, and a worker started from one has an opaque origin, which may not import the glue.
  let start: string | undefined;
  moduleOptions.locateFile = (path, prefix) => {
    if (!path.endsWith('.worker.js')) return prefix + path;
    start ??= URL.createObjectURL(new Blob([`importScripts(${JSON.stringify(pthreadWorker)});`], { type: 'text/javascript' }));
    return start;
  };
  return ((await import(/* @vite-ignore */ glue)) as { default: RawFactory }).default;
}

async function createRaw(options: InitOptions): Promise<RawModule> {
  const threads = threadsFor(options);
  const moduleOptions: RawModuleOptions = {};
  let failInstantiate: (e: unknown) => void = () => {};
  const instantiateFailed = new Promise<never>((_, reject) => {
    failInstantiate = reject;
  });

  const fileUrl = options.wasmUrl === undefined || String(options.wasmUrl).startsWith('file:');
  const readFile = platform().readFile;
  if (options.wasmBinary) {
    moduleOptions.wasmBinary = options.wasmBinary;
  } else if (readFile && !options.wasmModule && fileUrl) {
    moduleOptions.wasmBinary = await readFile(options.wasmUrl === undefined ? wasmLocation() : new URL(String(options.wasmUrl)));
  } else {
    const { wasmModule, wasmUrl } = options;
    // the module goes with the instance: the threaded glue posts it to its pthread workers
    moduleOptions.instantiateWasm = (imports, receive) => {
      const source = wasmModule
        ? WebAssembly.instantiate(wasmModule, imports).then((instance) => ({ instance, module: wasmModule }))
        : instantiateFromUrl(wasmUrl ?? wasmLocation(threads > 1), imports);
      source.then((s) => receive(s.instance, s.module), failInstantiate);
      return {};
    };
  }
  // The glue prints only on aborts; keep that on stderr rather than losing it.
  moduleOptions.print = (text) => console.log(text);
  moduleOptions.printErr = (text) => console.warn(text);
  const factory = threads > 1 ? await threadedFactory(threads, moduleOptions) : createConformeshModule;
  const raw = await Promise.race([factory(moduleOptions), instantiateFailed]);
  raw.threads = threads;
  return raw;
}

let pending: Promise<RawModule> | undefined;

/**
 * The shared raw module, created on first use. Options are honoured on the first call only;
 * a failed load is not cached (the next call tries again).
 */
export function loadRaw(options: InitOptions = {}): Promise<RawModule> {
  if (!pending) {
    pending = createRaw(options).catch((e: unknown) => {
      pending = undefined;
      const message = e instanceof Error ? e.message : String(e);
      // the browser entry imported in Node (e.g. dist/browser.js by path) fetches a file: URL
      const hint = isNode() && !platform().readFile ? " (in Node, import 'conformesh' or its Node entry dist/index.js)" : '';
      throw new ConformeshError('IoError', 'api', `cannot load the conformesh WebAssembly module: ${message}${hint}`);
    });
  }
  return pending;
}

/** A new, independent module instance (own heap) — what each worker uses. */
export function createRawInstance(options: InitOptions = {}): Promise<RawModule> {
  return createRaw(options);
}
