// Building the three views' scene content from meshes and per-triangle data, and repainting the
// per-triangle colours when the selection or the toggles change.
import {
  BufferAttribute,
  BufferGeometry,
  DataTexture,
  DoubleSide,
  Group,
  LineBasicMaterial,
  LineSegments,
  Mesh,
  MeshBasicMaterial,
  MeshStandardMaterial,
  Points,
  PointsMaterial,
  RepeatWrapping,
  SRGBColorSpace,
  type Object3D,
} from 'three';
import { toBufferGeometry } from 'conformesh/three';
import type { FlatPatch, Mesh3 } from './engine.ts';
import { minAngleColor, patchColor, ramp, type RGB } from './colors.ts';
import { packBoxes, patchBox, type Box2 } from './atlas.ts';

/** The surface material of the 3D views (pushed back so that lines over it show), plus `extra`. */
function surfaceMaterial(extra: ConstructorParameters<typeof MeshStandardMaterial>[0]): MeshStandardMaterial {
  return new MeshStandardMaterial({
    metalness: 0,
    side: DoubleSide,
    polygonOffset: true,
    polygonOffsetFactor: 1,
    polygonOffsetUnits: 1,
    ...extra,
  });
}

/** A non-indexed triangle mesh (one colour per triangle) with flat shading. */
export function faceColoredMesh(mesh: Mesh3): Mesh {
  const indexed = toBufferGeometry({ positions: mesh.positions, triangles: mesh.triangles });
  const geometry = indexed.toNonIndexed();
  indexed.dispose();
  geometry.deleteAttribute('normal');
  geometry.computeVertexNormals();
  geometry.setAttribute('color', new BufferAttribute(new Float32Array(mesh.triangles.length * 3), 3));
  return new Mesh(geometry, surfaceMaterial({ vertexColors: true, flatShading: true, roughness: 0.85 }));
}

/** True when the mesh has texture coordinates (per vertex, or per corner at uv seams). */
export function hasUv(mesh: Mesh3): boolean {
  return !!mesh.uvs || !!mesh.attributes?.some((a) => a.name === 'uv' && a.itemSize === 2);
}

let checker: DataTexture | undefined;

/** A checker texture, 16 × 16 cells over [0, 1]² (shared by every textured mesh). */
function checkerTexture(): DataTexture {
  if (checker) return checker;
  const n = 256, cells = 16;
  const data = new Uint8Array(4 * n * n);
  for (let y = 0; y < n; ++y)
    for (let x = 0; x < n; ++x) {
      const on = ((Math.floor((x * cells) / n) + Math.floor((y * cells) / n)) & 1) === 1;
      data.set(on ? [40, 44, 52, 255] : [235, 228, 205, 255], 4 * (y * n + x));
    }
  checker = new DataTexture(data, n, n);
  checker.wrapS = checker.wrapT = RepeatWrapping;
  checker.colorSpace = SRGBColorSpace;
  checker.needsUpdate = true;
  return checker;
}

/**
 * The mesh with a checker texture through its uvs (conformesh/three splits the vertices on uv
 * seams), smooth shaded: distortion and seams of the texture mapping show.
 */
export function texturedMesh(mesh: Mesh3): Mesh {
  return new Mesh(toBufferGeometry(mesh), surfaceMaterial({ map: checkerTexture(), roughness: 0.9 }));
}

/** Set triangle f's colour in a faceColoredMesh. */
export function paintFaces(mesh: Mesh, colorOf: (f: number) => RGB): void {
  const attr = mesh.geometry.getAttribute('color') as BufferAttribute;
  const c = attr.array as Float32Array;
  const nF = c.length / 9;
  for (let f = 0; f < nF; ++f) {
    const [r, g, b] = colorOf(f);
    for (let k = 0; k < 3; ++k) {
      c[9 * f + 3 * k] = r;
      c[9 * f + 3 * k + 1] = g;
      c[9 * f + 3 * k + 2] = b;
    }
  }
  attr.needsUpdate = true;
}

/**
 * Every edge of a triangle list once, as vertex pairs (2 per edge). Sorting numeric keys keeps
 * this a few milliseconds for 10^5 triangles (three's WireframeGeometry builds a string per edge
 * and took 30-130 ms on a 7k-triangle remesh).
 */
export function uniqueEdges(triangles: Uint32Array, vertexCount: number): Uint32Array {
  const keys = new Float64Array(triangles.length);
  for (let f = 0; f < triangles.length; f += 3) {
    for (let k = 0; k < 3; ++k) {
      const a = triangles[f + k]!, b = triangles[f + (k === 2 ? 0 : k + 1)]!;
      keys[f + k] = a < b ? a * vertexCount + b : b * vertexCount + a;
    }
  }
  keys.sort();
  const out: number[] = [];
  for (let i = 0; i < keys.length; ++i) {
    if (i > 0 && keys[i] === keys[i - 1]) continue;
    const a = Math.floor(keys[i]! / vertexCount);
    out.push(a, keys[i]! - a * vertexCount);
  }
  return Uint32Array.from(out);
}

export function wireframe(mesh: Mesh3, color: number, opacity: number): LineSegments {
  return edgeLines(mesh.positions, uniqueEdges(mesh.triangles, mesh.positions.length / 3), color, opacity);
}

/** Line segments between vertex pairs (2·n indices) of positions (3 per vertex). */
export function edgeLines(positions: ArrayLike<number>, pairs: Uint32Array, color: number, opacity = 1): LineSegments {
  const p = new Float32Array(pairs.length * 3);
  for (let i = 0; i < pairs.length; ++i) {
    const v = pairs[i]!;
    p[3 * i] = positions[3 * v]!;
    p[3 * i + 1] = positions[3 * v + 1]!;
    p[3 * i + 2] = positions[3 * v + 2]!;
  }
  const g = new BufferGeometry();
  g.setAttribute('position', new BufferAttribute(p, 3));
  return new LineSegments(g, new LineBasicMaterial({ color, transparent: opacity < 1, opacity }));
}

/**
 * Dots of a fixed size on screen at the given points (3 coordinates each), drawn over the
 * surface (no depth test: a corner behind the mesh is still shown). The exempt corners.
 */
export function cornerMarkers(points: ArrayLike<number>, color: number): Points {
  const g = new BufferGeometry();
  g.setAttribute('position', new BufferAttribute(Float32Array.from(points), 3));
  const dots = new Points(g, new PointsMaterial({ color, size: 9, sizeAttenuation: false, depthTest: false, transparent: true }));
  dots.renderOrder = 10;
  return dots;
}

/**
 * One small object of every material kind a view draws (same builders, so the same shader
 * programs): a viewport compiles them at start-up and keeps them, so that a remesh's new scenes
 * never wait for a shader compile (with a software GL, 250-700 ms per view).
 */
export function materialSamples(mode: '3d' | '2d'): Object3D[] {
  const tri: Mesh3 = { positions: Float64Array.of(0, 0, 0, 1, 0, 0, 0, 1, 0), triangles: Uint32Array.of(0, 1, 2) };
  if (mode === '3d') return [faceColoredMesh(tri), wireframe(tri, 0, 0.5), edgeLines(tri.positions, Uint32Array.of(0, 1), 0), cornerMarkers(tri.positions, 0)];
  const uv = Float64Array.of(0, 0, 1, 0, 0, 1);
  const scene = flatScene([
    { id: 0, layout: { uv, triangles: tri.triangles, factor: Float64Array.of(0, 1, 0) }, refined: { uv, triangles: tri.triangles } },
    { id: 1, layout: { uv, triangles: tri.triangles } },
  ]);
  return [...scene.group.children];
}

/** Colour of an input triangle: its patch (or neutral), brightened when selected, dimmed when another patch is. */
export function selectionShade(base: RGB, patch: number | undefined, selected: number | undefined): RGB {
  if (selected === undefined || patch === undefined) return base;
  if (patch === selected) return [0.35 + 0.65 * base[0], 0.35 + 0.65 * base[1], 0.35 + 0.65 * base[2]];
  return [base[0] * 0.35, base[1] * 0.35, base[2] * 0.35];
}

export const NEUTRAL: RGB = [0.7, 0.72, 0.76];
export { minAngleColor, patchColor };

export interface FlatScene {
  group: Group;
  /** Whether any patch carries the conformal factor (fills coloured by it, else by patch). */
  hasFactor: boolean;
  /** Filled meshes, one per patch (pickable; userData.patch is the patch id). */
  fills: Mesh[];
  layoutLines: LineSegments[];
  refinedLines: LineSegments[];
  factorRange: [number, number];
}

/** Planar positions (2 per vertex) moved by (dx, dy), as 3D positions at z = 0. */
function planarPositions(uv: Float64Array, dx: number, dy: number): Float32Array {
  const n = uv.length / 2;
  const p = new Float32Array(3 * n);
  for (let i = 0; i < n; ++i) {
    p[3 * i] = uv[2 * i]! + dx;
    p[3 * i + 1] = uv[2 * i + 1]! + dy;
  }
  return p;
}

function planarGeometry(uv: Float64Array, triangles: Uint32Array, dx: number, dy: number): BufferGeometry {
  const g = new BufferGeometry();
  g.setAttribute('position', new BufferAttribute(planarPositions(uv, dx, dy), 3));
  g.setIndex(new BufferAttribute(Uint32Array.from(triangles), 1));
  return g;
}

function planarLines(uv: Float64Array, triangles: Uint32Array, dx: number, dy: number, color: number, opacity: number): LineSegments {
  return edgeLines(planarPositions(uv, dx, dy), uniqueEdges(triangles, uv.length / 2), color, opacity);
}

/**
 * Every patch's planar mesh, packed side by side (shelf packing by height), filled with the
 * conformal factor (log area element 2u on one colour scale for all patches), with the input
 * layout and the refined planar mesh as separate line sets.
 */
export function flatScene(patches: FlatPatch[]): FlatScene {
  const group = new Group();
  const scene: FlatScene = { group, hasFactor: false, fills: [], layoutLines: [], refinedLines: [], factorRange: [0, 0] };
  const items = patches
    .map((p) => ({ p, uv: p.layout?.uv ?? p.refined?.uv, box: patchBox(p) }))
    .filter((x): x is { p: FlatPatch; uv: Float64Array; box: Box2 } => !!x.uv && x.uv.length >= 6 && !!x.box);
  let fmin = Infinity, fmax = -Infinity;
  for (const { p } of items) {
    const f = p.layout?.factor ?? p.refined?.factor;
    if (f) for (let i = 0; i < f.length; ++i) { fmin = Math.min(fmin, f[i]!); fmax = Math.max(fmax, f[i]!); }
  }
  scene.hasFactor = Number.isFinite(fmin);
  scene.factorRange = scene.hasFactor ? [fmin, fmax] : [0, 0];
  // the same packing as the UV atlas of the OBJ export (atlas.ts)
  const moves = packBoxes(items.map((x) => x.box));
  const span = scene.factorRange[1] - scene.factorRange[0];
  for (const [i, { p }] of items.entries()) {
    const { dx, dy } = moves[i]!;
    const fillSrc = p.layout ?? p.refined!;
    const g = planarGeometry(fillSrc.uv, fillSrc.triangles, dx, dy);
    const n = fillSrc.uv.length / 2;
    const col = new Float32Array(3 * n);
    const base = patchColor(p.id);
    for (let v = 0; v < n; ++v) {
      const c = fillSrc.factor ? ramp(span > 0 ? (fillSrc.factor[v]! - scene.factorRange[0]) / span : 0.5) : base;
      col[3 * v] = c[0]; col[3 * v + 1] = c[1]; col[3 * v + 2] = c[2];
    }
    g.setAttribute('color', new BufferAttribute(col, 3));
    g.userData.baseColors = col.slice();
    const fill = new Mesh(g, new MeshBasicMaterial({ vertexColors: true, side: DoubleSide, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 }));
    fill.userData.patch = p.id;
    group.add(fill);
    scene.fills.push(fill);
    if (p.layout) {
      const l = planarLines(p.layout.uv, p.layout.triangles, dx, dy, 0xffffff, 0.35);
      l.userData.patch = p.id;
      group.add(l);
      scene.layoutLines.push(l);
    }
    if (p.refined) {
      const l = planarLines(p.refined.uv, p.refined.triangles, dx, dy, 0xff9a3c, 0.8);
      l.position.z = 0.001;
      l.userData.patch = p.id;
      group.add(l);
      scene.refinedLines.push(l);
    }
  }
  return scene;
}

/** Dim every patch fill but the selected one. */
export function paintFlat(scene: FlatScene, selected: number | undefined): void {
  for (const fill of scene.fills) {
    const attr = fill.geometry.getAttribute('color') as BufferAttribute;
    const base = fill.geometry.userData.baseColors as Float32Array;
    const c = attr.array as Float32Array;
    const k = selected === undefined || fill.userData.patch === selected ? 1 : 0.3;
    for (let i = 0; i < c.length; ++i) c[i] = base[i]! * k;
    attr.needsUpdate = true;
  }
}
