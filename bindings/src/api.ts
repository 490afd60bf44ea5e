// The synchronous API over one module instance: the methods of the table (methods.ts), bound to
// the module, and the module's own tables. Each method checks its arguments (a wrong type is an
// InvalidArgument ConformeshError, never a crash inside the module), copies them into the shapes
// the glue expects, calls the glue through callRaw, and returns plain JS values.
import { bindMethods, type DirectMethods } from './methods.js';
import type { RawModule } from './raw.js';
import type { RemeshSchema } from './schema.js';
import type { StatusRow } from './types.js';

export { toBytes, toMesh, toPslg, pickOptions } from './convert.js';

/**
 * The API bound to one module instance; every method is synchronous. Obtain it with `init()`.
 * The methods and their documentation: METHODS in methods.ts.
 */
export interface Conformesh extends DirectMethods {
  /** Library version ("0.1.0"). */
  readonly version: string;
  /** Threads a call runs on: above 1 in the threaded build (InitOptions.threads), else 1. */
  readonly threads: number;
  /** The C++ status table. */
  statusTable(): StatusRow[];
  /** The C++ tables of remesh's options (name, kind, default, range, CLI flag, help) and report fields. */
  remeshSchema(): RemeshSchema;
  /** Bytes allocated in the module's heap, and the WASM memory size (for leak checks). */
  heapStats(): { used: number; heapSize: number };
}

/** Bind the API to a raw module instance. */
export function bindApi(raw: RawModule): Conformesh {
  const api: Conformesh = {
    version: raw.version(),
    threads: raw.threads ?? 1,
    ...bindMethods(raw),
    statusTable: () => raw.statusTable(),
    remeshSchema: () => raw.remeshSchema(),
    heapStats: () => raw.heapStats(),
  };
  return Object.freeze(api);
}
