// The progress/cancel bridge that long-running bindings use (bindings/src/progress.ts with
// bindings/binding_util.h progressFromJs), driven by the module's progressSelfTest.
import { describe, expect, it } from 'vitest';
import { ConformeshError } from '../../dist/index.js';
import { createRawInstance } from '../../dist/loader.js';
import { progressBridge, type ProgressOptions } from '../../dist/progress.js';
import { callRaw } from '../../dist/raw.js';

const raw = await createRawInstance();

function run(steps: number, options: ProgressOptions) {
  const bridge = progressBridge(options);
  try {
    return callRaw(raw, 'progressSelfTest', 'api', () => raw.progressSelfTest(steps, bridge.fn));
  } finally {
    bridge.rethrow();
  }
}

describe('progress bridge', () => {
  it('reports fractions monotone in [0, 1], ending at 1', () => {
    const f: number[] = [];
    expect(run(50, { onProgress: (e) => f.push(e.fraction) })).toBe(50);
    expect(f.length).toBe(50);
    expect(f.every((x, i) => x >= 0 && x <= 1 && (i === 0 || x >= f[i - 1]!))).toBe(true);
    expect(f.at(-1)).toBe(1);
  });

  it('an abort during the call stops it with Cancelled at the next report', () => {
    const ac = new AbortController();
    let seen = 0;
    const e = (() => {
      try {
        run(1000, { signal: ac.signal, onProgress: () => (++seen === 10 ? ac.abort() : undefined) });
      } catch (x) {
        return x;
      }
    })() as ConformeshError;
    expect(e).toBeInstanceOf(ConformeshError);
    expect(e.code).toBe('Cancelled');
    expect(seen).toBe(10);
    const pre = new AbortController();
    pre.abort();
    expect(() => run(10, { signal: pre.signal })).toThrow(/cancelled/);
  });

  it('a throwing listener cancels the call; its own error reaches the caller; heap and stack stay flat', () => {
    const usedBefore = raw.heapStats().used;
    const sp = raw.stackSave();
    for (let i = 0; i < 2000; ++i) {
      expect(() =>
        run(100, {
          onProgress: (e) => {
            if (e.fraction > 0.5) throw new RangeError('listener failed');
          },
        }),
      ).toThrow(RangeError);
    }
    expect(raw.stackSave()).toBe(sp);
    expect(raw.heapStats().used).toBe(usedBefore);
  });
});
