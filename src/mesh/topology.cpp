#include "mesh/topology.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "mesh/edge_groups.h"
#include "mesh/mesh_checks.h"
#include "core/detmath.h"

namespace conformesh {

Components connectedComponents(const HalfedgeMesh& mesh) {
  Components c;
  c.faceComponent = FaceData<uint32_t>(mesh, detail::kNone);
  c.vertexComponent = VertexData<uint32_t>(mesh, detail::kNone);
  std::vector<FaceId> stack;
  for (FaceId seed : mesh.faces()) {
    if (c.faceComponent[seed] != detail::kNone) continue;
    const uint32_t id = uint32_t(c.count++);
    c.faceComponent[seed] = id;
    stack.assign(1, seed);
    while (!stack.empty()) {
      FaceId f = stack.back();
      stack.pop_back();
      for (HalfedgeId h : mesh.faceHalfedges(f)) {
        c.vertexComponent[mesh.tail(h)] = id;
        FaceId g = mesh.face(mesh.twin(h));
        if (g.valid() && c.faceComponent[g] == detail::kNone) {
          c.faceComponent[g] = id;
          stack.push_back(g);
        }
      }
    }
  }
  return c;
}

std::vector<std::vector<HalfedgeId>> boundaryLoops(const HalfedgeMesh& mesh) {
  std::vector<std::vector<HalfedgeId>> loops;
  std::vector<uint8_t> seen(mesh.halfedgeCount(), 0);
  for (HalfedgeId h : mesh.halfedges()) {
    if (!mesh.isBoundary(h) || seen[h.idx()]) continue;
    std::vector<HalfedgeId> loop;
    for (HalfedgeId g : mesh.loopHalfedges(h)) {
      seen[g.idx()] = 1;
      loop.push_back(g);
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

long eulerCharacteristic(const HalfedgeMesh& mesh) {
  long v = 0;
  for (VertexId x : mesh.vertices()) v += mesh.isIsolated(x) ? 0 : 1;
  return v - long(mesh.edgeCount()) + long(mesh.faceCount());
}

long genus(const HalfedgeMesh& mesh) {
  const long c = long(connectedComponents(mesh).count);
  const long b = long(boundaryLoops(mesh).size());
  return (2 * c - eulerCharacteristic(mesh) - b) / 2;
}

namespace {
// Summed as x + (y + z), Eigen's unvectorized order, so the angles keep their bits.
double dotYzFirst(const Vec3& a, const Vec3& b) { return a.x * b.x + (a.y * b.y + a.z * b.z); }
}  // namespace

EdgeData<double> dihedralAngles(const HalfedgeMesh& mesh, const VertexData<Vec3>& pos) {
  EdgeData<double> angle(mesh, 0.0);
  for (EdgeId e : mesh.edges()) {
    if (mesh.isBoundary(e)) continue;
    HalfedgeId h = mesh.halfedge(e);
    Vec3 n1 = faceAreaNormal(mesh, pos, mesh.face(h));
    Vec3 n2 = faceAreaNormal(mesh, pos, mesh.face(mesh.twin(h)));
    Vec3 d = edgeVector(mesh, pos, h);
    double len = std::sqrt(dotYzFirst(d, d));
    if (len == 0.0 || dotYzFirst(n1, n1) == 0.0 || dotYzFirst(n2, n2) == 0.0) continue;
    angle[e] = dmath::atan2(dotYzFirst(cross(n1, n2), d) / len, dotYzFirst(n1, n2));
  }
  return angle;
}

EdgeData<uint8_t> sharpEdges(const HalfedgeMesh& mesh, const VertexData<Vec3>& pos, double threshold) {
  EdgeData<double> a = dihedralAngles(mesh, pos);
  EdgeData<uint8_t> sharp(mesh, 0);
  for (EdgeId e : mesh.edges()) sharp[e] = std::fabs(a[e]) > threshold ? 1 : 0;
  return sharp;
}

MeshInfo meshInfo(const MeshBuffers& m, const ValidateOptions& limits) {
  using detail::kNone;
  detail::checkBuffers(m, limits.maxVertices, limits.maxTriangles, Stage::Validate);
  const size_t nv = m.vertexCount();
  MeshInfo info;

  detail::FaceFilter ff = detail::filterDegenerateFaces(m, true);
  const std::vector<uint32_t>& tris = ff.tris;
  info.degenerateFaces = ff.repeatedVertex + ff.zeroArea;
  info.faces = tris.size() / 3;
  if (info.degenerateFaces > 0)
    info.warnings.push_back({Code::DegenerateFace, info.degenerateFaces,
                             std::to_string(info.degenerateFaces) + " degenerate triangles (" +
                                 std::to_string(ff.repeatedVertex) + " with a repeated vertex, " +
                                 std::to_string(ff.zeroArea) + " with zero area), e.g. triangle " +
                                 std::to_string(ff.firstDegenerate) + "; left out of the counts"});

  detail::Duplicates dup = detail::findDuplicateFaces(tris);
  info.duplicateFaces = dup.count;
  if (dup.count > 0)
    info.warnings.push_back({Code::NonManifoldEdge, dup.count,
                             std::to_string(dup.count) + " duplicate triangles, e.g. triangle " +
                                 std::to_string(ff.faceToInput[dup.first]) + " repeats triangle " +
                                 std::to_string(ff.faceToInput[dup.firstOriginal])});

  detail::EdgeStats es = detail::edgeStats(detail::groupEdges(nv, tris), tris);
  info.edges = es.edges;
  info.nonManifoldEdges = es.nonManifoldEdges;
  if (es.nonManifoldEdges > 0) {
    uint32_t c = es.firstNonManifoldCorner;
    info.warnings.push_back({Code::NonManifoldEdge, es.nonManifoldEdges,
                             std::to_string(es.nonManifoldEdges) + " edges are shared by more than two triangles, e.g. (" +
                                 std::to_string(std::min(tris[c], detail::cornerTip(tris, c))) + ", " +
                                 std::to_string(std::max(tris[c], detail::cornerTip(tris, c))) + ") by " +
                                 std::to_string(es.firstNonManifoldFaces)});
  }

  detail::Orientation o = detail::orientFaces(tris, es.partner);
  info.inconsistentFaces = o.flipped;
  if (o.flipped > 0)
    info.warnings.push_back({Code::InconsistentOrientation, o.flipped,
                             std::to_string(o.flipped) + " triangles disagree with the orientation of their neighbours (" +
                                 std::to_string(o.inconsistentEdges) + " edges); validation reverses them"});
  if (o.nonOrientableComponents > 0)
    info.warnings.push_back({Code::InvalidTopology, o.nonOrientableComponents,
                             std::to_string(o.nonOrientableComponents) +
                                 " connected parts are not orientable (Möbius strip or Klein bottle), e.g. the part of triangle " +
                                 std::to_string(ff.faceToInput[o.firstNonOrientableFace])});

  detail::Fans fans = detail::vertexFans(nv, tris, es.partner);
  info.nonManifoldVertices = fans.bowtieVertices;
  if (fans.bowtieVertices > 0)
    info.warnings.push_back({Code::NonManifoldVertex, fans.bowtieVertices,
                             std::to_string(fans.bowtieVertices) + " bow-tie vertices (several fans of triangles), e.g. vertex " +
                                 std::to_string(fans.firstBowtie)});
  fans = detail::Fans();

  // Vertices and components.
  std::vector<uint8_t> used(nv, 0);
  for (uint32_t v : tris) used[v] = 1;
  detail::UnionFind uf(nv);
  for (size_t f = 0; f < info.faces; ++f) {
    uf.unite(tris[3 * f], tris[3 * f + 1]);
    uf.unite(tris[3 * f], tris[3 * f + 2]);
  }
  size_t unused = 0;
  for (size_t v = 0; v < nv; ++v) {
    if (!used[v]) {
      ++unused;
      continue;
    }
    ++info.vertices;
    if (uf.find(uint32_t(v)) == v) ++info.components;
  }
  if (unused > 0)
    info.warnings.push_back({Code::Ok, unused, std::to_string(unused) + " vertices are not used by any triangle"});

  // Boundary loops: cycle rank of the boundary-edge graph.
  {
    detail::UnionFind bf(nv);
    std::vector<uint8_t> onBoundary(nv, 0);
    size_t eb = es.boundaryCorners.size(), vb = 0, cb = 0;
    for (uint32_t c : es.boundaryCorners) {
      uint32_t a = tris[c], b = detail::cornerTip(tris, c);
      onBoundary[a] = onBoundary[b] = 1;
      bf.unite(a, b);
    }
    for (size_t v = 0; v < nv; ++v) {
      if (!onBoundary[v]) continue;
      ++vb;
      if (bf.find(uint32_t(v)) == v) ++cb;
    }
    info.boundaryLoops = eb - vb + cb;
  }

  info.euler = long(info.vertices) - long(info.edges) + long(info.faces);
  info.genus = (2.0 * double(info.components) - double(info.euler) - double(info.boundaryLoops)) / 2.0;
  return info;
}

}  // namespace conformesh
