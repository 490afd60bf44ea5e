// The quality panel's one table: every value it shows, by key, with the words a user reads, its
// unit and its group (Input / Output / Pipeline). Keys are the library report's own paths
// (RemeshReport: 'minAngle', 'seconds.flatten', 'exemptCorners', …) or, for what the page
// measures itself on the loaded mesh, 'input.*'. Nothing else in the page holds a label: the
// table rows and the tests come from here, the stages' rows and bar names from the package's
// stage table (STAGES).
import { REMESH_STAGES, STAGES, type RemeshReport } from 'conformesh';

export type Group = 'input' | 'output' | 'pipeline';
export const GROUPS: readonly { group: Group; title: string }[] = [
  { group: 'input', title: 'Input' },
  { group: 'output', title: 'Output' },
  { group: 'pipeline', title: 'Pipeline' },
];

/**
 * How a value is shown: 'count' an integer; 'deg' degrees; 'pct' a percentage the report gives in
 * [0, 100]; 'frac' a share in [0, 1]; 'rel' a length relative to the input's bounding-box
 * diagonal (negative: not computed); 'length' in the mesh's units; 's' seconds; 'yesno' a
 * boolean; 'counts' a list of counts (min–max and total); 'list' the number of items; 'text'
 * strings.
 */
export type Unit = 'count' | 'deg' | 'pct' | 'frac' | 'rel' | 'length' | 's' | 'yesno' | 'counts' | 'list' | 'text';

export interface QualityEntry {
  key: string;
  label: string;
  unit: Unit;
  group: Group;
  /** What the number means, for the row's tooltip. */
  hint?: string;
}

export const QUALITY: readonly QualityEntry[] = [
  // ---- input: the page's measures of the loaded mesh, then what the remesher found in it
  { key: 'input.vertices', label: 'vertices', unit: 'count', group: 'input' },
  { key: 'input.triangles', label: 'triangles', unit: 'count', group: 'input' },
  { key: 'input.minAngle', label: 'smallest angle', unit: 'deg', group: 'input' },
  { key: 'input.maxAngle', label: 'largest angle', unit: 'deg', group: 'input' },
  { key: 'input.meanMin', label: 'mean smallest angle per triangle', unit: 'deg', group: 'input' },
  { key: 'input.below30', label: 'angles below 30°', unit: 'frac', group: 'input' },
  { key: 'input.below20', label: 'angles below 20°', unit: 'frac', group: 'input' },
  { key: 'input.components', label: 'connected pieces', unit: 'count', group: 'input' },
  { key: 'input.genus', label: 'genus (handles)', unit: 'count', group: 'input' },
  { key: 'input.boundaryLoops', label: 'boundary loops (holes)', unit: 'count', group: 'input' },
  { key: 'inputVertices', label: 'vertices the remesher used', unit: 'count', group: 'input', hint: 'after the library\u2019s repair and welding' },
  { key: 'inputTriangles', label: 'triangles the remesher used', unit: 'count', group: 'input', hint: 'after the library\u2019s repair' },
  { key: 'sharpEdges', label: 'edges sharper than the feature angle', unit: 'count', group: 'input' },
  { key: 'droppedFeatureEdges', label: 'sharp edges not kept as creases', unit: 'count', group: 'input', hint: 'too short or too weak to be a crease (see minFeatureLength)' },
  { key: 'featureCurves', label: 'feature curves found', unit: 'count', group: 'input' },
  { key: 'exemptCorners', label: 'corners sharper than the bound (exempt)', unit: 'list', group: 'input', hint: 'input corners whose angle is below the angle bound: the triangles touching them cannot meet it' },
  // ---- output: the library's report on the remesh
  { key: 'vertices', label: 'vertices', unit: 'count', group: 'output' },
  { key: 'triangles', label: 'triangles', unit: 'count', group: 'output' },
  { key: 'minAngle', label: 'smallest angle', unit: 'deg', group: 'output' },
  { key: 'minAngleOutsideExempt', label: 'smallest angle away from exempt corners', unit: 'deg', group: 'output' },
  { key: 'trianglesBelowBoundOutsideExempt', label: 'triangles below the bound away from exempt corners', unit: 'count', group: 'output' },
  { key: 'maxAngle', label: 'largest angle', unit: 'deg', group: 'output' },
  { key: 'meanMinAngle', label: 'mean smallest angle per triangle', unit: 'deg', group: 'output' },
  { key: 'pctBelow20', label: 'angles below 20°', unit: 'pct', group: 'output' },
  { key: 'pctBelow26', label: 'angles below 26°', unit: 'pct', group: 'output' },
  { key: 'pctBelow30', label: 'angles below 30°', unit: 'pct', group: 'output' },
  { key: 'pctMinAtLeast40', label: 'triangles with every angle ≥ 40°', unit: 'pct', group: 'output' },
  { key: 'pctMinAtLeast50', label: 'triangles with every angle ≥ 50°', unit: 'pct', group: 'output' },
  { key: 'hausdorffRel', label: 'distance to the input, two-sided (× diagonal)', unit: 'rel', group: 'output', hint: 'sampled Hausdorff distance over the bounding-box diagonal' },
  { key: 'maxDistanceToInputRel', label: 'farthest vertex from the input (× diagonal)', unit: 'rel', group: 'output' },
  { key: 'meanEdgeLength', label: 'mean edge length', unit: 'length', group: 'output' },
  { key: 'targetEdgeLength', label: 'target edge length', unit: 'length', group: 'output' },
  { key: 'delaunayFraction', label: 'edges that are Delaunay in 3D', unit: 'frac', group: 'output' },
  { key: 'featureCurvesKept', label: 'feature curves kept', unit: 'count', group: 'output' },
  { key: 'seamEdges', label: 'uv seam edges kept as curves', unit: 'count', group: 'output', hint: 'edges where the file\u2019s texture coordinates (or other per-corner data) jump: kept so that no triangle straddles one' },
  { key: 'topologyPreserved', label: 'same topology as the input', unit: 'yesno', group: 'output' },
  // ---- pipeline: how the library got there
  { key: 'patches', label: 'patches flattened', unit: 'count', group: 'pipeline' },
  { key: 'cutEdges', label: 'cut edges between patches', unit: 'count', group: 'pipeline' },
  { key: 'curves', label: 'curves meshed', unit: 'count', group: 'pipeline' },
  { key: 'curveSamples', label: 'points placed on the curves', unit: 'count', group: 'pipeline' },
  { key: 'flowIterations', label: 'conformal flow iterations per patch', unit: 'counts', group: 'pipeline' },
  { key: 'patchSplitsForScale', label: 'patch splits to bound the scale', unit: 'count', group: 'pipeline' },
  { key: 'sinkCuts', label: 'patches cut through a sink of the scale or a spike tip', unit: 'count', group: 'pipeline' },
  { key: 'patchJoins', label: 'narrow patches joined to a neighbour', unit: 'count', group: 'pipeline' },
  { key: 'estimatedTriangles', label: 'triangles estimated before refining', unit: 'count', group: 'pipeline' },
  { key: 'conformingRounds', label: 'conforming rounds', unit: 'count', group: 'pipeline' },
  { key: 'certificateRounds', label: '3D angle check rounds', unit: 'count', group: 'pipeline' },
  { key: 'optimizeMoves', label: 'vertex moves by the optimization', unit: 'count', group: 'pipeline' },
  { key: 'optimizeFlips', label: 'edge flips by the optimization', unit: 'count', group: 'pipeline' },
  { key: 'optimizeSplits', label: 'vertices added by the optimization', unit: 'count', group: 'pipeline' },
  { key: 'optimizeCollapses', label: 'edges collapsed by the optimization', unit: 'count', group: 'pipeline' },
  { key: 'repairMoves', label: 'vertices moved to repair an angle', unit: 'count', group: 'pipeline' },
  ...REMESH_STAGES.map((s): QualityEntry => ({ key: `seconds.${s.key}`, label: `time: ${s.label}`, unit: 's', group: 'pipeline' })),
  { key: 'seconds.total', label: 'time: total in the library', unit: 's', group: 'pipeline' },
  { key: 'page.seconds', label: 'time: click to result (page clock)', unit: 's', group: 'pipeline', hint: 'includes the worker round trip' },
  { key: 'warnings', label: 'warnings', unit: 'text', group: 'pipeline' },
];

const BY_KEY = new Map(QUALITY.map((e) => [e.key, e]));

/** The table's entry of a key (undefined: the table does not know it). */
export function entryOf(key: string): QualityEntry | undefined {
  return BY_KEY.get(key);
}

/** A value the table can show. */
export type Value = number | boolean | string | readonly unknown[] | ArrayLike<number> | undefined;

/** A value in its unit, as text ('—' when missing). */
export function formatValue(unit: Unit, v: Value): string {
  if (v === undefined || v === null) return '—';
  if (unit === 'list') return String((v as ArrayLike<unknown>).length);
  if (unit === 'text') {
    const items = typeof v === 'string' ? [v] : Array.from(v as ArrayLike<unknown>, String);
    return items.length ? items.join('; ') : 'none';
  }
  if (unit === 'counts') {
    const xs = Array.from(v as ArrayLike<number>);
    if (xs.length === 0) return 'none';
    const total = xs.reduce((a, b) => a + b, 0);
    return `${Math.min(...xs)}–${Math.max(...xs)} (${total} in all)`;
  }
  if (unit === 'yesno') return v ? 'yes' : 'no';
  if (typeof v !== 'number' || !Number.isFinite(v)) return '—';
  switch (unit) {
    case 'count': return String(v);
    case 'deg': return `${v.toFixed(2)}°`;
    case 'pct': return `${v.toFixed(2)}%`;
    case 'frac': return `${(100 * v).toFixed(2)}%`;
    case 'rel': return v < 0 ? 'not computed' : v.toExponential(2);
    case 's': return `${v.toFixed(3)} s`;
    case 'length': return v.toPrecision(4);
  }
  return String(v);
}

/**
 * The report's values by key: top-level fields, and one level of nested objects as 'a.b'
 * (seconds.*). Arrays are values of their own (flowIterations, exemptCorners, warnings).
 */
export function reportValues(report: RemeshReport): Map<string, Value> {
  const out = new Map<string, Value>();
  for (const [k, v] of Object.entries(report)) {
    if (v && typeof v === 'object' && !Array.isArray(v) && !ArrayBuffer.isView(v)) {
      for (const [k2, v2] of Object.entries(v as Record<string, Value>)) out.set(`${k}.${k2}`, v2);
    } else out.set(k, v as Value);
  }
  return out;
}

/** A stage's name as a key: 'curve-mesh' (progress events) and 'curveMesh' (report.seconds) are one stage. */
export function stageKey(name: string): string {
  return name.toLowerCase().replace(/[^a-z0-9]/g, '');
}

/** The stages whose times the report gives, in its order ('total' is no stage). */
export function reportedStages(report: RemeshReport): string[] {
  return Object.keys(report.seconds ?? {}).filter((k) => k !== 'total');
}

/** The bar name of a stage (the library's label), else its name in words. */
export function stageLabel(name: string): string {
  const key = stageKey(name);
  const row = STAGES.find((s) => stageKey(s.name) === key);
  return row?.label ?? name.replace(/([a-z])([A-Z])/g, '$1 $2').replace(/-/g, ' ').toLowerCase();
}
