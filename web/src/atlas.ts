// The patches side by side in one plane: the packing the flattened-domain view draws, and the
// same packing scaled into [0, 1]² as a UV atlas of the remesh (OBJ `vt` / `f v/vt`).
import type { FlatPatch, Mesh3 } from './engine.ts';

/** Axis-aligned box [x0, y0, x1, y1]. */
export type Box2 = [number, number, number, number];

export function box2(uv: Float64Array, into: Box2 = [Infinity, Infinity, -Infinity, -Infinity]): Box2 {
  for (let i = 0; i < uv.length; i += 2) {
    into[0] = Math.min(into[0], uv[i]!); into[2] = Math.max(into[2], uv[i]!);
    into[1] = Math.min(into[1], uv[i + 1]!); into[3] = Math.max(into[3], uv[i + 1]!);
  }
  return into;
}

/** The box around a patch's input layout and its refined mesh (undefined: no planar data). */
export function patchBox(p: FlatPatch): Box2 | undefined {
  if (!p.layout && !p.refined) return undefined;
  const b: Box2 = [Infinity, Infinity, -Infinity, -Infinity];
  if (p.layout) box2(p.layout.uv, b);
  if (p.refined) box2(p.refined.uv, b);
  return b[0] <= b[2] && b[1] <= b[3] ? b : undefined;
}

/**
 * Shelf packing: boxes sorted by height, placed left to right in rows about 1.6·sqrt(total area)
 * wide, rows going down, with a gap of 6 % of the mean box side between boxes. Returns the
 * translation of every box (input order). Boxes never overlap: each row starts below the
 * tallest box of the row above, each box right of the previous one plus the gap.
 */
export function packBoxes(boxes: Box2[]): { dx: number; dy: number }[] {
  let area = 0, maxDim = 0;
  for (const b of boxes) {
    area += (b[2] - b[0]) * (b[3] - b[1]);
    maxDim = Math.max(maxDim, b[2] - b[0], b[3] - b[1]);
  }
  const gap = 0.06 * Math.sqrt(area / Math.max(1, boxes.length));
  const rowWidth = Math.max(maxDim, 1.6 * Math.sqrt(area));
  const order = boxes.map((_, i) => i).sort((a, b) => boxes[b]![3] - boxes[b]![1] - (boxes[a]![3] - boxes[a]![1]));
  const out = boxes.map(() => ({ dx: 0, dy: 0 }));
  let x = 0, y = 0, rowH = 0;
  for (const i of order) {
    const b = boxes[i]!;
    const w = b[2] - b[0], h = b[3] - b[1];
    if (x > 0 && x + w > rowWidth) { x = 0; y -= rowH + gap; rowH = 0; }
    out[i] = { dx: x - b[0], dy: y - b[3] };
    x += w + gap;
    rowH = Math.max(rowH, h);
  }
  return out;
}

export interface UvAtlas {
  /** 2 per atlas vertex, in [0, 1]²: one atlas vertex per refined planar vertex of every patch. */
  uv: Float64Array;
  /** 3 per output triangle: the atlas vertex of each corner (same corner order as the triangle). */
  corners: Uint32Array;
}

/**
 * A UV atlas of the remesh from its patches' refined planar meshes: every patch keeps its
 * conformal coordinates, translated by the flattened view's packing and scaled by one factor into
 * [0, 1]² (so the patches' texel densities keep their ratios and no two patches overlap). A
 * vertex on a cut or a patch border gets one UV per patch. Undefined when the result carries no
 * refined patches; throws when the patches do not match the output triangles.
 */
export function uvAtlas(mesh: Mesh3, patches: FlatPatch[], patchOfTriangle: Uint32Array | undefined): UvAtlas | undefined {
  const nT = mesh.triangles.length / 3;
  if (!patchOfTriangle || patchOfTriangle.length !== nT || patches.length === 0) return undefined;
  const byId = new Map<number, FlatPatch>();
  for (const p of patches) {
    if (!p.refined?.outputVertex) return undefined;
    byId.set(p.id, p);
  }
  const list = [...byId.values()];
  const boxes: Box2[] = [];
  for (const p of list) {
    const b = patchBox(p);
    if (!b) throw new Error(`patch ${p.id} has no finite planar coordinates: no UV atlas for this remesh`);
    boxes.push(b);
  }
  const moves = packBoxes(boxes);
  let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
  boxes.forEach((b, i) => {
    const { dx, dy } = moves[i]!;
    x0 = Math.min(x0, b[0] + dx); x1 = Math.max(x1, b[2] + dx);
    y0 = Math.min(y0, b[1] + dy); y1 = Math.max(y1, b[3] + dy);
  });
  const scale = 1 / Math.max(x1 - x0, y1 - y0, Number.MIN_VALUE);
  const first = new Map<number, number>(); // patch id -> its first atlas vertex
  let n = 0;
  for (const p of list) { first.set(p.id, n); n += p.refined!.uv.length / 2; }
  const uv = new Float64Array(2 * n);
  const clamp01 = (v: number) => Math.min(1, Math.max(0, v));
  list.forEach((p, i) => {
    const src = p.refined!.uv, base = 2 * first.get(p.id)!, { dx, dy } = moves[i]!;
    for (let k = 0; k < src.length; k += 2) {
      uv[base + k] = clamp01((src[k]! + dx - x0) * scale);
      uv[base + k + 1] = clamp01((src[k + 1]! + dy - y0) * scale);
    }
  });
  // the k-th output triangle of a patch is the k-th triangle of its refined mesh
  const next = new Map<number, number>();
  const corners = new Uint32Array(3 * nT);
  for (let t = 0; t < nT; ++t) {
    const id = patchOfTriangle[t]!;
    const p = byId.get(id);
    if (!p) throw new Error(`uv atlas: output triangle ${t} is in patch ${id}, which the result does not carry`);
    const k = next.get(id) ?? 0;
    next.set(id, k + 1);
    const { triangles, outputVertex } = p.refined! as { triangles: Uint32Array; outputVertex: Uint32Array };
    if (3 * k + 2 >= triangles.length) throw new Error(`uv atlas: patch ${id} has fewer planar triangles than output triangles`);
    for (let c = 0; c < 3; ++c) {
      const local = triangles[3 * k + c]!;
      if (outputVertex[local] !== mesh.triangles[3 * t + c]) {
        throw new Error(`uv atlas: corner ${c} of output triangle ${t} is not its planar triangle's (patch ${id})`);
      }
      corners[3 * t + c] = first.get(id)! + local;
    }
  }
  return { uv, corners };
}

/**
 * An OBJ with the atlas: the library's plain OBJ of the same mesh (its `v` lines and everything
 * else kept byte for byte), with `vt` lines before the first face and `f v/vt v/vt v/vt` faces.
 * Throws when the OBJ's faces are not the mesh's triangles in order.
 */
export function objWithUvs(plainObj: string, mesh: Mesh3, atlas: UvAtlas): string {
  const lines = plainObj.split('\n');
  const out: string[] = [];
  let face = 0;
  for (const line of lines) {
    if (!line.startsWith('f ')) {
      out.push(line);
      continue;
    }
    if (face === 0) {
      for (let i = 0; i < atlas.uv.length; i += 2) out.push(`vt ${atlas.uv[i]} ${atlas.uv[i + 1]}`);
    }
    const v = line.slice(2).trim().split(/\s+/).map(Number);
    if (v.length !== 3 || v.some((x, c) => x !== mesh.triangles[3 * face + c]! + 1)) {
      throw new Error(`OBJ with UVs: face ${face + 1} of the written OBJ is not triangle ${face} of the remesh`);
    }
    out.push(`f ${v.map((x, c) => `${x}/${atlas.corners[3 * face + c]! + 1}`).join(' ')}`);
    ++face;
  }
  if (face !== mesh.triangles.length / 3) throw new Error(`OBJ with UVs: the written OBJ has ${face} faces, the remesh ${mesh.triangles.length / 3}`);
  return out.join('\n');
}
