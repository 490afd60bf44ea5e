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
import createConformeshModule from './conformesh.mjs';
import { platform } from './platform.js';
import type { RawModule, RawModuleOptions } from './raw.js';
import { ConformeshError } from './status.js';

export interface InitOptions {
  /** The .wasm bytes (skips fetching / reading the file). */
  wasmBinary?: ArrayBuffer | Uint8Array;
  /** A compiled module (e.g. posted from the main thread to a worker). */
  wasmModule?: WebAssembly.Module;
  /** Where to fetch the .wasm from (default: next to this file). */
  wasmUrl?: string | URL;
}

/** True in Node.js (not in browsers, workers or bundles that polyfill `process`). */
export function isNode(): boolean {
  const p = (globalThis as { process?: { versions?: { node?: string }; release?: { name?: string } } }).process;
  return typeof p?.versions?.node === 'string' && p.release?.name === 'node';
}

/** The .wasm file next to the package's scripts. */
export function wasmLocation(): URL {
  return new URL('./conformesh.wasm', import.meta.url);
}

async function instantiateFromUrl(url: URL | string, imports: WebAssembly.Imports): Promise<WebAssembly.Instance> {
  const response = await fetch(url, { credentials: 'same-origin' });
  if (!response.ok) throw new Error(`cannot fetch ${String(url)}: HTTP ${response.status}`);
  const type = response.headers.get('content-type') ?? '';
  if (typeof WebAssembly.instantiateStreaming === 'function' && type.startsWith('application/wasm')) {
    return (await WebAssembly.instantiateStreaming(response, imports)).instance;
  }
  return (await WebAssembly.instantiate(await response.arrayBuffer(), imports)).instance;
}

async function createRaw(options: InitOptions): Promise<RawModule> {
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
    moduleOptions.instantiateWasm = (imports, receive) => {
      const instance = wasmModule
        ? WebAssembly.instantiate(wasmModule, imports)
        : instantiateFromUrl(wasmUrl ?? wasmLocation(), imports);
      instance.then((i) => receive(i), failInstantiate);
      return {};
    };
  }
  // The glue prints only on aborts; keep that on stderr rather than losing it.
  moduleOptions.print = (text) => console.log(text);
  moduleOptions.printErr = (text) => console.warn(text);
  return Promise.race([createConformeshModule(moduleOptions), instantiateFailed]);
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
