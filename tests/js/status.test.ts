import { describe, expect, it } from 'vitest';
import { ConformeshError, init, StatusCode } from '../../dist/index.js';

// One table: C++ (include/conformesh/status.h). The TypeScript union must agree with the module's export.
describe('status table', () => {
  it('the TypeScript StatusCode union equals the module statusTable(), name for name and value for value', async () => {
    const cm = await init();
    const table = cm.statusTable();
    expect(table.length).toBeGreaterThan(10);
    expect(Object.fromEntries(table.map((r) => [r.name, r.code]))).toEqual(StatusCode);
  });

  it('ConformeshError carries code, numeric value, stage and message, and survives a JSON round trip', () => {
    const e = new ConformeshError('ParseError', 'read', 'line 3: expected a number');
    expect(e).toBeInstanceOf(Error);
    expect(e.name).toBe('ConformeshError');
    expect(e.value).toBe(StatusCode.ParseError);
    const back = ConformeshError.fromData(JSON.parse(JSON.stringify(e)));
    expect(back.toJSON()).toEqual(e.toJSON());
    expect(ConformeshError.fromData({ code: 'Nope' as never, message: 'x' }).code).toBe('InternalError');
  });
});
