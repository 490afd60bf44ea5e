// The method table (bindings/src/methods.ts) and the surfaces derived from it: every method of the
// table is on the direct API, the lazy async functions, the Remesher and the worker's dispatch,
// and every method follows one error model: a non-Ok status throws ConformeshError, with the
// partial result attached when the glue gives one.
import { afterAll, describe, expect, it } from 'vitest';
import * as pkg from '../../dist/index.js';
import { ConformeshError, createRemesher, init } from '../../dist/index.js';
import { bindApi } from '../../dist/api.js';
import { METHOD_NAMES, METHODS } from '../../dist/methods.js';
import type { WorkerResponse } from '../../dist/protocol.js';
import type { RawModule } from '../../dist/raw.js';
import { createWorkerHandler } from '../../dist/worker.js';

const triangle = { positions: new Float64Array([0, 0, 0, 1, 0, 0, 0, 1, 0]), triangles: new Uint32Array([0, 1, 2]) };

/** Arguments that pass every check of the facade, per method: a new method needs a row here. */
const validArgs: Record<string, unknown[]> = {
  readMesh: [new TextEncoder().encode('v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n'), 'obj'],
  writeMesh: [triangle, 'off'],
  meshInfo: [triangle],
  validateMesh: [triangle],
  refine2d: [{ points: [0, 0, 1, 0, 0, 1], segments: [0, 1, 1, 2, 2, 0] }],
  readPoly: [new TextEncoder().encode('3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n0 0\n0\n')],
  flatten: [triangle],
  remesh: [triangle],
};

/** A module whose every glue function answers `answer` (the facade's checks still run first). */
function fakeRaw(answer: () => unknown): RawModule {
  const raw: Record<string, unknown> = {
    version: () => '0.0.0',
    statusTable: () => [],
    remeshSchema: () => ({}),
    stageTable: () => [],
    heapStats: () => ({ used: 0, heapSize: 0 }),
    stackSave: () => 0,
    stackRestore: () => {},
  };
  for (const name of METHOD_NAMES) raw[name] = answer;
  return raw as unknown as RawModule;
}

function thrown(f: () => unknown): unknown {
  try {
    f();
  } catch (e) {
    return e;
  }
  throw new Error('expected a throw');
}

describe('the method table', () => {
  const remesher = createRemesher();
  afterAll(() => remesher.terminate());

  it('lists methods, each with a stage and one send kind per argument', () => {
    expect(METHOD_NAMES.length).toBeGreaterThan(0);
    for (const name of METHOD_NAMES) {
      const row = METHODS[name];
      expect(typeof row.run, name).toBe('function');
      expect(row.send.length, name).toBeGreaterThan(0);
      // run(raw, call, ...args): the declared parameters are the send kinds' arguments plus two
      expect(row.run.length, name).toBe(row.send.length + 2);
      expect(validArgs[name], `validArgs has no row for ${name}`).toBeDefined();
    }
  });

  it('every method is on the direct API, the async functions, the Remesher and the worker', async () => {
    const cm = await init();
    const handle = createWorkerHandler();
    for (const name of METHOD_NAMES) {
      expect(typeof (cm as unknown as Record<string, unknown>)[name], `direct ${name}`).toBe('function');
      expect(typeof (pkg as Record<string, unknown>)[name], `async ${name}`).toBe('function');
      expect(typeof (remesher as unknown as Record<string, unknown>)[name], `Remesher ${name}`).toBe('function');
      // the worker serves it: a call with bad arguments is an argument error, not an unknown method
      const answers: WorkerResponse[] = [];
      await handle({ id: 1, type: 'call', method: name, args: [42] }, (m) => answers.push(m));
      const last = answers.at(-1)!;
      expect(last.type, `worker ${name}`).toBe('error');
      if (last.type === 'error') {
        expect(last.error.code).toBe('InvalidArgument');
        expect(last.error.message).not.toMatch(/unknown method/);
      }
    }
    for (const name of ['version', 'threads'] as const) {
      const answers: WorkerResponse[] = [];
      await handle({ id: 2, type: 'call', method: name, args: [] }, (m) => answers.push(m));
      expect(answers.at(-1)).toMatchObject({ type: 'result', value: cm[name] });
      expect(await remesher[name]()).toBe(cm[name]);
    }
  });

  it('a bad first argument is an InvalidArgument ConformeshError on every surface', async () => {
    const cm = await init();
    for (const name of METHOD_NAMES) {
      const direct = thrown(() => (cm[name] as (...a: unknown[]) => unknown)(42));
      expect(direct, name).toBeInstanceOf(ConformeshError);
      expect(direct, name).toMatchObject({ code: 'InvalidArgument' });
      const lazy = await ((pkg as Record<string, unknown>)[name] as (...a: unknown[]) => Promise<unknown>)(42).catch((e) => e);
      expect(lazy, name).toBeInstanceOf(ConformeshError);
      expect(lazy, name).toMatchObject({ code: 'InvalidArgument' });
      const viaWorker = await (remesher[name] as (...a: unknown[]) => Promise<unknown>)(42).catch((e) => e);
      expect(viaWorker, name).toBeInstanceOf(ConformeshError);
      expect(viaWorker, name).toMatchObject({ code: 'InvalidArgument' });
    }
  });
});

describe('one error model for every method', () => {
  it('a result whose status is not Ok throws that code, the result attached', () => {
    for (const name of METHOD_NAMES) {
      const value = { status: 'NotConverged', message: `${name} stopped`, partial: new Float64Array([1, 2]) };
      const api = bindApi(fakeRaw(() => ({ ok: true, value })));
      const e = thrown(() => (api[name] as (...a: unknown[]) => unknown)(...validArgs[name]!));
      expect(e, name).toBeInstanceOf(ConformeshError);
      expect(e, name).toMatchObject({ code: 'NotConverged', message: `${name} stopped`, stage: METHODS[name].stage });
      expect((e as ConformeshError).result, name).toBe(value);
    }
  });

  it('a failure from the glue throws its code and stage, with its partial result when it has one', () => {
    for (const name of METHOD_NAMES) {
      const partial = { mesh: triangle };
      const api = bindApi(
        fakeRaw(() => ({ ok: false, code: 12, name: 'IterationLimit', stage: 'refine', message: 'cap', result: partial })),
      );
      const e = thrown(() => (api[name] as (...a: unknown[]) => unknown)(...validArgs[name]!));
      expect(e, name).toMatchObject({ code: 'IterationLimit', stage: 'refine', message: 'cap' });
      expect((e as ConformeshError).result, name).toBe(partial);
      const bare = bindApi(fakeRaw(() => ({ ok: false, code: 2, name: 'ParseError', stage: 'read', message: 'line 1' })));
      const f = thrown(() => (bare[name] as (...a: unknown[]) => unknown)(...validArgs[name]!));
      expect(f, name).toMatchObject({ code: 'ParseError', stage: 'read' });
      expect((f as ConformeshError).result, name).toBeUndefined();
    }
  });

  it('a value with status Ok, or with no status, is returned', () => {
    for (const name of METHOD_NAMES) {
      for (const value of [{ status: 'Ok', message: '' }, { positions: new Float64Array(3) }]) {
        const api = bindApi(fakeRaw(() => ({ ok: true, value })));
        expect(() => (api[name] as (...a: unknown[]) => unknown)(...validArgs[name]!), name).not.toThrow();
      }
    }
  });
});
