// One stage table: C++ (include/conformesh/stages.h). The TypeScript copy (bindings/src/stages.ts), the
// report's seconds, the progress events and the docs' list must agree with the module's export.
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { init, REMESH_STAGES, Stage, STAGES, stageInterval, type ProgressEvent } from '../../dist/index.js';
import { createRawInstance } from '../../dist/loader.js';
import { dataFile, root } from './helpers.js';

describe('stage table', () => {
  it('the TypeScript STAGES equal the module stageTable(), row for row, and Stage its values', async () => {
    const raw = await createRawInstance();
    const rows = raw.stageTable();
    expect(STAGES.map((s, i) => ({ stage: i, ...s }))).toEqual(rows.map(({ lo: _lo, hi: _hi, ...r }) => r));
    expect(Object.fromEntries(rows.map((s) => [s.name, s.stage]))).toEqual(Stage);
    for (const r of rows) expect(stageInterval(r.name as never), r.name).toEqual({ lo: r.lo, hi: r.hi });
  });

  it('a remesh reports its seconds per stage in the table\u2019s order, and its progress in that order', async () => {
    const cm = await init();
    const mesh = cm.readMesh(dataFile('ALSTOM_TEST4.off'), 'off');
    const events: ProgressEvent[] = [];
    const r = cm.remesh(mesh, { computeHausdorff: false, targetEdgeLengthRel: 0.02 }, { onProgress: (e) => events.push(e) });
    expect(Object.keys(r.report.seconds)).toEqual([...REMESH_STAGES.map((s) => s.key), 'total']);
    const order = STAGES.map((s) => s.name as string);
    const seen = events.map((e) => order.indexOf(e.stage));
    for (let i = 1; i < seen.length; ++i) expect(seen[i]!).toBeGreaterThanOrEqual(seen[i - 1]!);
    // every stage that reports progress of its own did (ALSTOM_TEST4, coarse CAD, at 0.02 takes certificate rounds and a repair)
    expect(r.report.repairMoves).toBeGreaterThan(0);
    expect(new Set(events.map((e) => e.stage))).toEqual(new Set(REMESH_STAGES.filter((s) => s.weight > 0).map((s) => s.name)));
  });

  it('docs/ARCHITECTURE.md lists the stages in the table\u2019s order', () => {
    const doc = readFileSync(join(root, 'docs', 'ARCHITECTURE.md'), 'utf8');
    const line = /^Stages[^:]*: (.*)\.$/m.exec(doc);
    expect(line, 'a "Stages: ..." line').not.toBeNull();
    expect(line![1]!.split(', ')).toEqual(STAGES.map((s) => s.name));
  });
});
