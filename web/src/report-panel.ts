// The demo page's report panels: the quality table in words and the list of exempt corners.
import type { RemeshReport } from 'conformesh';
import { GROUPS, QUALITY, entryOf, formatValue, stageLabel, type Unit, type Value } from './quality.ts';

type ExemptCorner = RemeshReport['exemptCorners'][number];

/** A value shown in red: the bound missed away from exempt corners, or the topology changed. */
function isBad(key: string, x: Value, bound: number): boolean {
  if (key === 'minAngleOutsideExempt') return typeof x === 'number' && x < bound - 1e-9;
  if (key === 'trianglesBelowBoundOutsideExempt') return typeof x === 'number' && x > 0;
  if (key === 'topologyPreserved') return x === false;
  return false;
}

/** The quality table in words (quality.ts QUALITY), grouped; bound: the angle bound of the values. */
export function renderQualityTable(table: HTMLElement, values: Map<string, Value>, bound: number): void {
  for (const old of table.querySelectorAll('tbody')) old.remove();
  const unknown = [...values.keys()].filter((k) => !entryOf(k));
  for (const { group, title } of GROUPS) {
    const body = document.createElement('tbody');
    body.dataset.group = group;
    const head = document.createElement('tr');
    head.className = 'group';
    const th = document.createElement('th');
    th.colSpan = 2;
    th.textContent = title;
    head.append(th);
    body.append(head);
    const entries: { key: string; label: string; unit: Unit; hint?: string; known: boolean }[] = QUALITY.filter((e) => e.group === group && values.get(e.key) !== undefined)
      .map((e) => ({ ...e, known: true }));
    // a key the library added and the table does not know yet: shown, in words, and flagged
    if (group === 'pipeline') for (const key of unknown) entries.push({ key, label: stageLabel(key), unit: 'text', known: false });
    for (const e of entries) {
      const x = values.get(e.key);
      const tr = document.createElement('tr');
      tr.dataset.key = e.key;
      if (!e.known) tr.dataset.unknown = 'true';
      if (e.hint) tr.title = e.hint;
      const name = document.createElement('td');
      name.textContent = e.label;
      const value = document.createElement('td');
      value.textContent = formatValue(e.unit, x);
      value.dataset.testid = `q-${e.key}`;
      if (isBad(e.key, x, bound)) value.className = 'bad';
      tr.append(name, value);
      body.append(tr);
    }
    if (entries.length === 0) {
      const tr = document.createElement('tr');
      const td = document.createElement('td');
      td.colSpan = 2;
      td.className = 'muted';
      td.textContent = group === 'input' ? 'load a mesh' : 'press Remesh';
      tr.append(td);
      body.append(tr);
    }
    table.append(body);
  }
}

/** The list of the report's exempt corners (input corners sharper than the bound). */
export function renderExemptList(list: HTMLElement, note: HTMLElement, corners: readonly ExemptCorner[] | undefined, bound: number, hasInput: boolean): void {
  list.replaceChildren();
  if (!corners) {
    note.textContent = hasInput ? 'Remesh to see them.' : '';
    return;
  }
  note.textContent = corners.length
    ? `${corners.length} input corner${corners.length === 1 ? '' : 's'} below the ${bound}° bound: the triangles touching ${corners.length === 1 ? 'it' : 'them'} cannot meet it. Magenta dots in views 1 and 3.`
    : `none: every triangle is held to the ${bound}° bound.`;
  for (const c of corners) {
    const li = document.createElement('li');
    li.dataset.vertex = String(c.vertex);
    li.dataset.outputVertex = String(c.outputVertex);
    li.dataset.angle = String(c.angle);
    li.textContent = `input vertex ${c.vertex} (output ${c.outputVertex}): corner of ${c.angle.toFixed(2)}°, ${c.triangles.length} triangle${c.triangles.length === 1 ? '' : 's'} exempt`;
    list.append(li);
  }
}

/** Positions (3 per corner) of the exempt corners' vertices in a mesh. */
export function exemptCornerPositions(positions: Float64Array, corners: readonly ExemptCorner[], which: 'vertex' | 'outputVertex'): Float64Array {
  const out = new Float64Array(3 * corners.length);
  corners.forEach((c, i) => out.set(positions.subarray(3 * c[which], 3 * c[which] + 3), 3 * i));
  return out;
}
