import { readFile } from 'node:fs/promises';
import { describe, expect, it } from 'vitest';

// The raw Emscripten module, as shipped in dist/ (the TypeScript facade is tested elsewhere).
describe('wasm module', () => {
  it('loads in Node ESM with the bytes passed in, and exports the status table', async () => {
    const { default: create } = await import('../../dist/conformesh.mjs');
    const wasmBinary = await readFile(new URL('../../dist/conformesh.wasm', import.meta.url));
    const m = await create({ wasmBinary });
    expect(m.version()).toMatch(/^\d+\.\d+\.\d+$/);
    const table = m.statusTable() as { code: number; name: string; fatal: boolean }[];
    expect(table[0]).toMatchObject({ code: 0, name: 'Ok', fatal: false });
    const names = new Set(table.map((r) => r.name));
    expect(names.size).toBe(table.length);
    expect(names.has('NonManifoldEdge')).toBe(true);
  });
});
