// conformesh/three — conversions between conformesh meshes and three.js BufferGeometry.
// three is an optional peer dependency: only this subpath imports it.
import { BufferAttribute, BufferGeometry } from 'three';
import { ConformeshError, invalidArgument } from './status.js';
import type { Mesh, MeshLike } from './types.js';

/**
 * A BufferGeometry with `position` (Float32, 3 per vertex), `index` (Uint32), `uv` when the mesh
 * has uvs, and vertex normals computed from the triangles. Positions are converted to float32
 * (three.js attributes); keep the Mesh for double-precision work.
 */
export function toBufferGeometry(mesh: MeshLike): BufferGeometry {
  if (typeof mesh !== 'object' || mesh === null || !mesh.positions || !mesh.triangles) {
    throw invalidArgument('toBufferGeometry: mesh must be { positions, triangles, uvs? }');
  }
  if (mesh.positions.length % 3 !== 0 || mesh.triangles.length % 3 !== 0) {
    throw invalidArgument('toBufferGeometry: positions and triangles lengths must be multiples of 3');
  }
  const nV = mesh.positions.length / 3;
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(Float32Array.from(mesh.positions), 3));
  const index = Uint32Array.from(mesh.triangles);
  for (let i = 0; i < index.length; ++i) {
    if (index[i]! >= nV) throw new ConformeshError('IndexOutOfRange', 'api', `triangles[${i}] = ${index[i]} >= ${nV} vertices`);
  }
  geometry.setIndex(new BufferAttribute(index, 1));
  if (mesh.uvs && mesh.uvs.length === 2 * nV) geometry.setAttribute('uv', new BufferAttribute(Float32Array.from(mesh.uvs), 2));
  geometry.computeVertexNormals();
  return geometry;
}

/**
 * A conformesh Mesh from a BufferGeometry's `position` (and `uv`) attributes and its index (a
 * non-indexed geometry is read as consecutive vertex triples; duplicated vertices are not merged:
 * readMesh/weld handles that for files). Interleaved attributes are supported.
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
  return mesh;
}
