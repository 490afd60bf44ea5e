// Progress and cancel for direct (same-thread) calls of long-running glue functions.
//
// C++ calls the JS progress function synchronously from inside the WASM call (ProgressFn,
// src/core/mesh_buffers.h): returning false cancels, and the library stops with Code::Cancelled.
// The function handed to C++ must never throw (a JS exception unwinding through C++ frames skips
// destructors): the user's listener is called inside try/catch, and what it threw is rethrown
// after the WASM call has returned.
import { stageName, type StageName } from './stages.js';
import { ConformeshError } from './status.js';

export interface ProgressOptions {
  onProgress?: ((event: { stage: StageName; fraction: number }) => void) | undefined;
  /** Checked at every progress report; already aborted: the call does not start. */
  signal?: AbortSignal | undefined;
}

export interface ProgressBridge {
  /** Pass to the glue function (or undefined when nobody listens). */
  fn: ((stage: number, fraction: number) => boolean) | undefined;
  /** After the glue call: rethrow what the listener threw, if anything. */
  rethrow(): void;
}

export function progressBridge(options: ProgressOptions | undefined): ProgressBridge {
  const signal = options?.signal;
  const listener = options?.onProgress;
  if (signal?.aborted) throw new ConformeshError('Cancelled', 'api', 'the call was cancelled before it started');
  let thrown: { error: unknown } | undefined;
  let last = 0;
  const fn =
    listener || signal
      ? (stage: number, fraction: number): boolean => {
          if (thrown) return false;
          try {
            const f = Math.min(1, Math.max(last, Number.isFinite(fraction) ? fraction : last));
            last = f;
            listener?.({ stage: stageName(stage), fraction: f });
          } catch (error) {
            thrown = { error };
            return false;
          }
          return !signal?.aborted;
        }
      : undefined;
  return {
    fn,
    rethrow() {
      if (thrown) throw thrown.error;
    },
  };
}
