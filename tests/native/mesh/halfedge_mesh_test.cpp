#include <doctest/doctest.h>

#include <algorithm>
#include <set>
#include <type_traits>

#include "mesh/halfedge_mesh.h"
#include "mesh_test_util.h"

using namespace conformesh;

namespace {
template <class Data, class H, class = void>
struct CanIndex : std::false_type {};
template <class Data, class H>
struct CanIndex<Data, H, std::void_t<decltype(std::declval<Data&>()[std::declval<H>()])>> : std::true_type {};
}  // namespace

TEST_CASE("handles of different kinds cannot be mixed") {
  static_assert(!std::is_convertible<VertexId, FaceId>::value, "VertexId -> FaceId");
  static_assert(!std::is_constructible<FaceId, VertexId>::value, "FaceId from VertexId");
  static_assert(!std::is_convertible<uint32_t, EdgeId>::value, "implicit index -> handle");
  static_assert(CanIndex<VertexData<int>, VertexId>::value, "VertexData[VertexId]");
  static_assert(!CanIndex<VertexData<int>, FaceId>::value, "VertexData[FaceId]");
  static_assert(!CanIndex<EdgeData<double>, HalfedgeId>::value, "EdgeData[HalfedgeId]");
  static_assert(sizeof(HalfedgeId) == 4, "compact handles");
  CHECK_FALSE(VertexId().valid());
  CHECK(VertexId(3u).idx() == 3u);
}

TEST_CASE("halfedge invariants hold on generated meshes, in any triangle and vertex order") {
  for (const auto& nm : test::generatedMeshes()) {
    for (uint32_t seed = 0; seed < 3; ++seed) {
      CAPTURE(nm.name);
      CAPTURE(seed);
      MeshBuffers m = seed == 0 ? nm.mesh : test::shuffled(nm.mesh, seed);
      HalfedgeMesh hm = HalfedgeMesh::fromTriangles(m.vertexCount(), m.triangles);
      CHECK_NOTHROW(hm.checkInvariants());
      REQUIRE(hm.faceCount() == m.triangleCount());
      CHECK(hm.toTriangles() == m.triangles);

      size_t boundary = 0;
      for (HalfedgeId h : hm.halfedges()) {
        CHECK(hm.twin(hm.twin(h)) == h);
        CHECK(hm.next(hm.prev(h)) == h);
        CHECK(hm.prev(hm.next(h)) == h);
        CHECK(hm.tail(hm.next(h)) == hm.tip(h));
        CHECK(hm.edge(hm.twin(h)) == hm.edge(h));
        CHECK(hm.findHalfedge(hm.tail(h), hm.tip(h)) == h);
        if (hm.isBoundary(h)) {
          ++boundary;
          CHECK_FALSE(hm.isBoundary(hm.twin(h)));
          CHECK(hm.isBoundary(hm.tail(h)));
        } else {
          CHECK(hm.next(hm.next(hm.next(h))) == h);
        }
      }
      CHECK(boundary == hm.boundaryHalfedgeCount());
      if (nm.loops == 0) CHECK(boundary == 0);
      if (nm.loops > 0) CHECK(boundary > 0);

      // Each face has exactly three halfedges, listing the triangle's corners in order.
      for (FaceId f : hm.faces()) {
        size_t n = 0;
        for (HalfedgeId h : hm.faceHalfedges(f)) {
          CHECK(hm.face(h) == f);
          CHECK(hm.tail(h).idx() == m.triangles[3 * f.idx() + n]);
          ++n;
        }
        CHECK(n == 3);
      }

      // Vertex circulation: outgoing halfedges = the halfedges starting there; faces = the triangles using v.
      std::vector<size_t> trianglesAt(m.vertexCount(), 0);
      for (uint32_t v : m.triangles) ++trianglesAt[v];
      std::vector<size_t> outgoing(m.vertexCount(), 0);
      for (HalfedgeId h : hm.halfedges()) ++outgoing[hm.tail(h).idx()];
      for (VertexId v : hm.vertices()) {
        size_t n = 0;
        std::set<uint32_t> neighbors;
        for (HalfedgeId h : hm.outgoingHalfedges(v)) {
          CHECK(hm.tail(h) == v);
          ++n;
        }
        for (VertexId w : hm.vertexNeighbors(v)) neighbors.insert(w.idx());
        CHECK(n == outgoing[v.idx()]);
        CHECK(n == hm.degree(v));
        CHECK(neighbors.size() == n);  // no repeated neighbour on a manifold
        CHECK_FALSE(hm.findHalfedge(v, v).valid());
        CHECK(hm.vertexFaces(v).size() == trianglesAt[v.idx()]);
        CHECK(hm.degree(v) == trianglesAt[v.idx()] + (hm.isBoundary(v) ? 1 : 0));
      }
    }
  }
}

TEST_CASE("fromTriangles rejects what is not an oriented manifold") {
  // Two triangles traversing their shared edge the same way.
  std::vector<uint32_t> sameWay = {0, 1, 2, 0, 1, 3};
  CHECK_THROWS_AS(HalfedgeMesh::fromTriangles(4, sameWay), Error);
  try {
    HalfedgeMesh::fromTriangles(4, sameWay);
  } catch (const Error& e) {
    CHECK(e.code() == Code::InconsistentOrientation);
  }
  auto codeOf = [](size_t nv, const std::vector<uint32_t>& t) {
    try {
      HalfedgeMesh::fromTriangles(nv, t);
    } catch (const Error& e) {
      return e.code();
    }
    return Code::Ok;
  };
  CHECK(codeOf(4, {0, 1, 2, 1, 0, 3, 0, 1, 3}) == Code::NonManifoldEdge);
  CHECK(codeOf(5, {0, 1, 2, 0, 3, 4}) == Code::NonManifoldVertex);  // two triangles touching at 0
  CHECK(codeOf(3, {0, 1, 3}) == Code::IndexOutOfRange);
  CHECK(codeOf(3, {0, 1, 1}) == Code::DegenerateFace);
  CHECK(codeOf(3, {0, 1, 2}) == Code::Ok);
  // Two closed tetrahedra sharing one vertex: every edge manifold, no boundary, two fans at 0.
  std::vector<uint32_t> tets = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 0, 5, 4, 0, 4, 6, 0, 6, 5, 4, 5, 6};
  CHECK(codeOf(7, tets) == Code::NonManifoldVertex);
}
