// conformesh/three — conversions between conformesh meshes and three.js BufferGeometry.
// three is an optional peer dependency: only this subpath imports it.
import { BufferAttribute, BufferGeometry } from 'three';
import { ConformeshError, invalidArgument } from './status.js';
import type { Mesh, MeshAttribute, MeshLike } from './types.js';

/** The three.js attribute name of a conformesh attribute: 'uv', 'normal' and 'color' as they are. */
function geometryName(name: string): string {
  return name === 'position' ? 'position_' : name;
}

/**
 * A BufferGeometry with `position` (Float32, 3 per vertex), `index` (Uint32), `uv` when the mesh
 * has uvs, one attribute per mesh attribute (Float32, its itemSize; 'uv', 'normal' and 'color' by
 * those names, the others by theirs), and vertex normals computed from the triangles when the mesh
 * has no 'normal'. three.js has one value per vertex: where a per-corner attribute (a uv seam) gives
 * a vertex several values, the vertex is split, one copy per distinct value set, and
 * `geometry.userData.meshVertex` (Uint32Array) gives the mesh vertex of every geometry vertex.
 * Positions are converted to float32 (three.js attributes); keep the Mesh for double-precision work.
 */
export function toBufferGeometry(mesh: MeshLike): BufferGeometry {
  if (typeof mesh !== 'object' || mesh === null || !mesh.positions || !mesh.triangles) {
    throw invalidArgument('toBufferGeometry: mesh must be { positions, triangles, uvs?, attributes? }');
  }
  if (mesh.positions.length % 3 !== 0 || mesh.triangles.length % 3 !== 0) {
    throw invalidArgument('toBufferGeometry: positions and triangles lengths must be multiples of 3');
  }
  const nV = mesh.positions.length / 3;
  const nC = mesh.triangles.length;
  const index = Uint32Array.from(mesh.triangles);
  for (let i = 0; i < index.length; ++i) {
    if (index[i]! >= nV) throw new ConformeshError('IndexOutOfRange', 'api', `triangles[${i}] = ${index[i]} >= ${nV} vertices`);
  }
  const attributes = mesh.attributes ?? [];
  for (const a of attributes) {
    const items = a.perCorner ? nC : nV;
    if (!(a.itemSize >= 1) || a.values.length !== items * a.itemSize) {
      throw invalidArgument(`toBufferGeometry: attribute '${a.name}' needs ${a.itemSize} values per ${a.perCorner ? 'corner' : 'vertex'}`);
    }
  }
  // split vertices where per-corner values differ: geometry vertex per (vertex, corner values)
  const corner = attributes.filter((a) => a.perCorner);
  let meshVertex: Uint32Array | undefined; // geometry vertex -> mesh vertex (when split)
  let firstCorner: Uint32Array | undefined; // geometry vertex -> a corner with its values
  if (corner.length > 0) {
    const ids = new Map<string, number>();
    const vertexOf: number[] = [];
    const cornerOf: number[] = [];
    for (let c = 0; c < nC; ++c) {
      let key = String(index[c]);
      for (const a of corner) for (let k = 0; k < a.itemSize; ++k) key += ',' + a.values[c * a.itemSize + k];
      let id = ids.get(key);
      if (id === undefined) {
        id = vertexOf.length;
        ids.set(key, id);
        vertexOf.push(index[c]!);
        cornerOf.push(c);
      }
      index[c] = id;
    }
    meshVertex = Uint32Array.from(vertexOf);
    firstCorner = Uint32Array.from(cornerOf);
  }
  const n = meshVertex ? meshVertex.length : nV;
  const gather = (values: ArrayLike<number>, itemSize: number, perCorner: boolean): Float32Array => {
    const out = new Float32Array(n * itemSize);
    for (let v = 0; v < n; ++v) {
      const item = perCorner ? firstCorner![v]! : meshVertex ? meshVertex[v]! : v;
      for (let k = 0; k < itemSize; ++k) out[v * itemSize + k] = values[item * itemSize + k]!;
    }
    return out;
  };
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(gather(mesh.positions, 3, false), 3));
  geometry.setIndex(new BufferAttribute(index, 1));
  if (mesh.uvs && mesh.uvs.length === 2 * nV) geometry.setAttribute('uv', new BufferAttribute(gather(mesh.uvs, 2, false), 2));
  for (const a of attributes) {
    geometry.setAttribute(geometryName(a.name), new BufferAttribute(gather(a.values, a.itemSize, a.perCorner === true), a.itemSize));
  }
  if (meshVertex) geometry.userData.meshVertex = meshVertex;
  if (!geometry.getAttribute('normal')) geometry.computeVertexNormals();
  return geometry;
}

/**
 * A conformesh Mesh from a BufferGeometry's `position` (and `uv`) attributes and its index (a
 * non-indexed geometry is read as consecutive vertex triples; duplicated vertices are not merged:
 * readMesh/weld handles that for files), with `normal` and `color` as per-vertex attributes.
 * Interleaved attributes are supported.
 */
export function fromBufferGeometry(geometry: BufferGeometry): Mesh {
  const position = geometry?.getAttribute?.('position');
  if (!position || position.itemSize !== 3) {
    throw invalidArgument('fromBufferGeometry: the geometry needs a position attribute with itemSize 3');
  }
  const nV = position.count;
  const positions = new Float64Array(3 * nV);
  for (let i = 0; i < nV; ++i) {
    positions[3 * i] = position.getX(i);
    positions[3 * i + 1] = position.getY(i);
    positions[3 * i + 2] = position.getZ(i);
  }
  let triangles: Uint32Array;
  const index = geometry.getIndex();
  if (index) {
    if (index.count % 3 !== 0) throw invalidArgument('fromBufferGeometry: index count is not a multiple of 3');
    triangles = new Uint32Array(index.count);
    for (let i = 0; i < index.count; ++i) triangles[i] = index.getX(i);
  } else {
    if (nV % 3 !== 0) throw invalidArgument('fromBufferGeometry: a non-indexed geometry needs 3 vertices per triangle');
    triangles = new Uint32Array(nV);
    for (let i = 0; i < nV; ++i) triangles[i] = i;
  }
  const mesh: Mesh = { positions, triangles };
  const uv = geometry.getAttribute('uv');
  if (uv && uv.itemSize === 2 && uv.count === nV) {
    const uvs = new Float64Array(2 * nV);
    for (let i = 0; i < nV; ++i) {
      uvs[2 * i] = uv.getX(i);
      uvs[2 * i + 1] = uv.getY(i);
    }
    mesh.uvs = uvs;
  }
  const attributes: MeshAttribute[] = [];
  for (const name of ['normal', 'color']) {
    const a = geometry.getAttribute(name);
    if (!a || a.count !== nV || a.itemSize < 1 || a.itemSize > 4) continue;
    const values = new Float64Array(nV * a.itemSize);
    for (let i = 0; i < nV; ++i) for (let k = 0; k < a.itemSize; ++k) values[i * a.itemSize + k] = a.getComponent(i, k);
    attributes.push({ name, itemSize: a.itemSize, perCorner: false, values });
  }
  if (attributes.length > 0) mesh.attributes = attributes;
  return mesh;
}
