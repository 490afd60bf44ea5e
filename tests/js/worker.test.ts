// createRemesher and the worker handler. The handler is tested directly (no worker), then the
// real thing: createRemesher in Node runs worker_threads Workers with dist/node-worker.js, the
// same handler as the module Web Worker (dist/worker.js) in browsers.
import { afterAll, describe, expect, it } from 'vitest';
import { ConformeshError, createRemesher, init, type ProgressEvent } from '../../dist/index.js';
import type { WorkerRequest, WorkerResponse } from '../../dist/protocol.js';
import { createWorkerHandler } from '../../dist/worker.js';
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { dataFile, root } from './helpers.js';

async function ask(request: WorkerRequest) {
  const handle = createWorkerHandler();
  const messages: { message: WorkerResponse; transfer: Transferable[] }[] = [];
  await handle(request, (message, transfer) => messages.push({ message, transfer }));
  return messages;
}

describe('worker handler (called directly)', () => {
  it('answers a call with progress ending at 1, then one result whose buffers are in the transfer list', async () => {
    const bytes = dataFile('spot.obj');
    const messages = await ask({ id: 7, type: 'call', method: 'readMesh', args: [bytes, 'obj'] });
    const progress = messages.filter((m) => m.message.type === 'progress');
    const last = messages.at(-1)!;
    expect(messages.every((m) => m.message.id === 7)).toBe(true);
    expect(progress.at(-1)?.message).toMatchObject({ type: 'progress', fraction: 1 });
    expect(last.message.type).toBe('result');
    const value = (last.message as { value: { positions: Float64Array; triangles: Uint32Array } }).value;
    expect(last.transfer).toContain(value.positions.buffer);
    expect(last.transfer).toContain(value.triangles.buffer);
    const direct = (await init()).readMesh(bytes, 'obj');
    expect(value.positions).toEqual(direct.positions);
    expect(value.triangles).toEqual(direct.triangles);
  });

  it('answers failures with error data (code, value, stage, message), and rejects unknown methods and types', async () => {
    const [parse] = await ask({ id: 1, type: 'call', method: 'readMesh', args: ['v 1 2 x\n', 'obj'] });
    expect(parse!.message).toMatchObject({ id: 1, type: 'error', error: { code: 'ParseError', value: 2, stage: 'read' } });
    const [unknown] = await ask({ id: 2, type: 'call', method: 'nope' as never, args: [] });
    expect(unknown!.message).toMatchObject({ id: 2, type: 'error', error: { code: 'InvalidArgument' } });
    const [bogus] = await ask({ id: 3, type: 'bogus' } as never);
    expect(bogus!.message).toMatchObject({ id: 3, type: 'error', error: { code: 'InvalidArgument' } });
  });
});

describe('createRemesher (real workers: worker_threads in Node)', () => {
  const remesher = createRemesher({ workers: 2 });
  afterAll(() => remesher.terminate());

  it('gives results identical to direct calls, for every API function', async () => {
    const cm = await init();
    const bytes = dataFile('fandisk.off');
    const direct = cm.readMesh(bytes);
    const viaWorker = await remesher.readMesh(bytes);
    expect(viaWorker.positions).toEqual(direct.positions);
    expect(viaWorker.triangles).toEqual(direct.triangles);
    expect(viaWorker.format).toBe(direct.format);
    expect(await remesher.writeMesh(direct, 'ply')).toEqual(cm.writeMesh(direct, 'ply'));
    expect(await remesher.version()).toBe(cm.version);
    expect(await remesher.meshInfo(direct)).toEqual(cm.meshInfo(direct));
    expect(await remesher.validateMesh(direct)).toEqual(cm.validateMesh(direct));
  });

  it('spreads concurrent calls over the workers and reports progress monotone in [0, 1], ending at 1', async () => {
    const names = ['spot.obj', 'fandisk.off', 't13_data.stl', 'holes.off', 'alligator.obj', 'blade.off'];
    const events: ProgressEvent[][] = names.map(() => []);
    const results = await Promise.all(
      names.map((n, i) => remesher.readMesh(dataFile(n), { fileName: n }, { onProgress: (e) => events[i]!.push(e) })),
    );
    const cm = await init();
    names.forEach((n, i) => {
      expect(results[i]!.triangles).toEqual(cm.readMesh(dataFile(n), { fileName: n }).triangles);
      const f = events[i]!.map((e) => e.fraction);
      expect(f.length).toBeGreaterThan(0);
      expect(f.every((x, k) => x >= 0 && x <= 1 && (k === 0 || x >= f[k - 1]!))).toBe(true);
      expect(f.at(-1)).toBe(1);
    });
  });

  it('rejects with ConformeshError from the worker, with code and stage', async () => {
    const e = await remesher.readMesh('v 0 0 0\nf 1 2 3\n', 'obj').catch((x: unknown) => x);
    expect(e).toBeInstanceOf(ConformeshError);
    expect((e as ConformeshError).code).toBe('IndexOutOfRange');
    expect((e as ConformeshError).stage).toBe('read');
  });

  it('cancel: an abort while running rejects with Cancelled at once, and the pool keeps working', async () => {
    const big = dataFile('stanford-bunny.obj');
    const ac = new AbortController();
    const t0 = performance.now();
    const call = remesher.readMesh(big, 'obj', { signal: ac.signal });
    setTimeout(() => ac.abort(), 5);
    const e = await call.catch((x: unknown) => x);
    expect((e as ConformeshError).code).toBe('Cancelled');
    expect(performance.now() - t0).toBeLessThan(1000);
    const again = await remesher.readMesh(dataFile('spot.obj'));
    expect(again.triangles.length).toBe(3 * 5856);
  });

  it('transfer: true moves the input buffers to the worker instead of copying', async () => {
    const bytes = dataFile('spot.obj').slice();
    const m = await remesher.readMesh(bytes, 'obj', { transfer: true });
    expect(bytes.byteLength).toBe(0);
    expect(m.triangles.length).toBe(3 * 5856);
  });

  it('after terminate(), pending and new calls reject with Cancelled', async () => {
    const r = createRemesher();
    const pending = r.readMesh(dataFile('stanford-bunny.obj'));
    r.terminate();
    expect(((await pending.catch((x: unknown) => x)) as ConformeshError).code).toBe('Cancelled');
    expect(((await r.version().catch((x: unknown) => x)) as ConformeshError).code).toBe('Cancelled');
  });

  it('idle Node workers do not keep the process alive (no terminate() needed to exit)', () => {
    const script = `
      import { createRemesher } from ${JSON.stringify(pathToFileURL(join(root, 'dist', 'index.js')).href)};
      const r = createRemesher();
      const m = await r.readMesh('v 0 0 0\\nv 1 0 0\\nv 0 1 0\\nf 1 2 3\\n', 'obj');
      console.log(m.triangles.length);
    `;
    const out = execFileSync(process.execPath, ['--input-type=module', '-e', script], { encoding: 'utf8', timeout: 30_000 });
    expect(out.trim()).toBe('3');
  });

  it('workers can share one compiled WebAssembly.Module (init: { wasmModule })', async () => {
    const wasmModule = await WebAssembly.compile(readFileSync(join(root, 'dist', 'conformesh.wasm')));
    const r = createRemesher({ init: { wasmModule } });
    try {
      expect((await r.readMesh(dataFile('spot.obj'))).triangles.length).toBe(3 * 5856);
    } finally {
      r.terminate();
    }
  });
});
