#include "mesh/halfedge_mesh.h"

#include <algorithm>
#include <string>

#include "mesh/edge_groups.h"

namespace conformesh {

namespace {
std::string faceText(const std::vector<uint32_t>& t, uint32_t f) {
  return "triangle " + std::to_string(f) + " (" + std::to_string(t[3 * f]) + " " +
         std::to_string(t[3 * f + 1]) + " " + std::to_string(t[3 * f + 2]) + ")";
}
void checkTriangles(size_t vertexCount, const std::vector<uint32_t>& t) {
  if (t.size() % 3 != 0)
    fail(Code::InvalidArgument, Stage::Validate, "triangle index array length is not a multiple of 3");
  // Halfedge ids are uint32 with 0xffffffff reserved; at most 6 halfedges per triangle.
  if (t.size() > size_t(0x7fffffff) || vertexCount >= size_t(0xffffffffu))
    fail(Code::TooLarge, Stage::Validate, "mesh too large for 32-bit halfedge indices");
  const uint32_t nf = uint32_t(t.size() / 3);
  for (uint32_t f = 0; f < nf; ++f) {
    for (int i = 0; i < 3; ++i)
      if (t[3 * f + i] >= vertexCount)
        fail(Code::IndexOutOfRange, Stage::Validate,
             faceText(t, f) + " refers to vertex " + std::to_string(t[3 * f + i]) + " but there are only " +
                 std::to_string(vertexCount) + " vertices");
    if (t[3 * f] == t[3 * f + 1] || t[3 * f + 1] == t[3 * f + 2] || t[3 * f] == t[3 * f + 2])
      fail(Code::DegenerateFace, Stage::Validate, faceText(t, f) + " repeats a vertex");
  }
}
}  // namespace

HalfedgeMesh HalfedgeMesh::fromTriangles(size_t vertexCount, const std::vector<uint32_t>& t) {
  checkTriangles(vertexCount, t);
  return fromGroupedTriangles(vertexCount, t, detail::groupEdges(vertexCount, t));
}

HalfedgeMesh HalfedgeMesh::fromGroupedTriangles(size_t vertexCount, const std::vector<uint32_t>& t,
                                                detail::EdgeGroups&& groups) {
  checkTriangles(vertexCount, t);
  const uint32_t nf = uint32_t(t.size() / 3);
  if (groups.corners.size() != t.size())
    fail(Code::InternalError, Stage::Validate, "edge groups do not match the triangles");
  const size_t ne = groups.groupCount();
  HalfedgeMesh m;
  m.next_.assign(2 * ne, HalfedgeId());
  m.prev_.assign(2 * ne, HalfedgeId());
  m.tail_.assign(2 * ne, VertexId());
  m.face_.assign(2 * ne, FaceId());
  m.vertexHalfedge_.assign(vertexCount, HalfedgeId());
  m.faceHalfedge_.assign(nf, HalfedgeId());

  std::vector<uint32_t> cornerHalfedge(t.size(), 0xffffffffu);
  for (size_t e = 0; e < ne; ++e) {
    const uint32_t* c = groups.corners.data() + groups.groupStart[e];
    const uint32_t n = groups.groupSize(e);
    for (uint32_t k = 0; k < n; ++k)
      if (c[k] >= t.size() || cornerHalfedge[c[k]] != 0xffffffffu)
        fail(Code::InternalError, Stage::Validate, "edge groups list a corner twice");
    for (uint32_t k = 1; k < n; ++k) {
      uint32_t a0 = t[c[0]], b0 = detail::cornerTip(t, c[0]), a = t[c[k]], b = detail::cornerTip(t, c[k]);
      if (!((a == a0 && b == b0) || (a == b0 && b == a0)))
        fail(Code::InternalError, Stage::Validate, "edge groups do not match the triangles");
    }
    if (n > 2) {
      uint32_t a = t[c[0]], b = detail::cornerTip(t, c[0]);
      std::string msg = "edge (" + std::to_string(std::min(a, b)) + ", " + std::to_string(std::max(a, b)) + ") is shared by " +
                        std::to_string(n) + " triangles:";
      for (uint32_t k = 0; k < n && k < 4; ++k) msg += " " + std::to_string(c[k] / 3);
      fail(Code::NonManifoldEdge, Stage::Validate, msg + (n > 4 ? " ..." : ""));
    }
    if (n == 2 && t[c[0]] == t[c[1]])
      fail(Code::InconsistentOrientation, Stage::Validate,
           faceText(t, c[0] / 3) + " and " + faceText(t, c[1] / 3) + " traverse edge (" +
               std::to_string(t[c[0]]) + ", " + std::to_string(detail::cornerTip(t, c[0])) +
               ") in the same direction");
    cornerHalfedge[c[0]] = uint32_t(2 * e);
    if (n == 2) cornerHalfedge[c[1]] = uint32_t(2 * e + 1);
  }
  groups = detail::EdgeGroups();  // free memory early

  // Interior halfedges.
  for (uint32_t f = 0; f < nf; ++f) {
    for (uint32_t i = 0; i < 3; ++i) {
      uint32_t h = cornerHalfedge[3 * f + i];
      uint32_t hn = cornerHalfedge[3 * f + (i + 1) % 3];
      m.next_[h] = HalfedgeId(hn);
      m.prev_[hn] = HalfedgeId(h);
      m.face_[h] = FaceId(f);
      m.tail_[h] = VertexId(t[3 * f + i]);
      m.vertexHalfedge_[t[3 * f + i]] = HalfedgeId(h);
    }
    m.faceHalfedge_[f] = HalfedgeId(cornerHalfedge[3 * f]);
  }
  cornerHalfedge = std::vector<uint32_t>();

  // Boundary halfedges: the faceless twin of an unpaired interior halfedge a->b runs b->a.
  // A manifold vertex has at most one outgoing boundary halfedge.
  std::vector<HalfedgeId> boundaryOut(vertexCount, HalfedgeId());
  for (uint32_t h = 1; h < 2 * ne; h += 2) {
    if (m.face_[h].valid()) continue;
    // Interior twin h^1 runs a->b (a = tail); this boundary halfedge runs b->a.
    uint32_t b = m.tail_[m.next_[h ^ 1u].idx()].idx();
    m.tail_[h] = VertexId(b);
    if (boundaryOut[b].valid())
      fail(Code::NonManifoldVertex, Stage::Validate,
           "vertex " + std::to_string(b) + " is on two boundary fans (bow-tie vertex)");
    boundaryOut[b] = HalfedgeId(h);
    ++m.boundaryHalfedgeCount_;
  }
  for (uint32_t h = 1; h < 2 * ne; h += 2) {
    if (m.face_[h].valid()) continue;
    VertexId a = m.tail_[h ^ 1u];  // tip of the boundary halfedge
    HalfedgeId n = boundaryOut[a.idx()];
    m.next_[h] = n;
    m.prev_[n.idx()] = HalfedgeId(h);
    m.vertexHalfedge_[a.idx()] = n;
  }

  // One fan per vertex: rotating from halfedge(v) must reach every outgoing halfedge.
  std::vector<uint32_t> outDegree(vertexCount, 0);
  for (uint32_t h = 0; h < 2 * ne; ++h) ++outDegree[m.tail_[h].idx()];
  for (uint32_t v = 0; v < vertexCount; ++v) {
    HalfedgeId h0 = m.vertexHalfedge_[v];
    if (!h0.valid()) continue;
    uint32_t count = 0;
    HalfedgeId h = h0;
    do {
      ++count;
      h = m.rotateCcw(h);
    } while (h != h0 && count <= outDegree[v]);
    if (count != outDegree[v])
      fail(Code::NonManifoldVertex, Stage::Validate,
           "vertex " + std::to_string(v) + " joins " + "separate fans of triangles (bow-tie vertex)");
  }
  return m;
}

size_t HalfedgeMesh::degree(VertexId v) const {
  size_t d = 0;
  for (HalfedgeId h : outgoingHalfedges(v)) {
    (void)h;
    ++d;
  }
  return d;
}

HalfedgeId HalfedgeMesh::findHalfedge(VertexId a, VertexId b) const {
  for (HalfedgeId h : outgoingHalfedges(a))
    if (tip(h) == b) return h;
  return HalfedgeId();
}

std::vector<FaceId> HalfedgeMesh::vertexFaces(VertexId v) const {
  std::vector<FaceId> out;
  for (HalfedgeId h : outgoingHalfedges(v))
    if (!isBoundary(h)) out.push_back(face(h));
  return out;
}

std::vector<uint32_t> HalfedgeMesh::toTriangles() const {
  std::vector<uint32_t> t(3 * faceCount());
  for (FaceId f : faces()) {
    auto vs = faceVertices(f);
    for (int i = 0; i < 3; ++i) t[3 * f.idx() + i] = vs[i].idx();
  }
  return t;
}

void HalfedgeMesh::checkInvariants() const {
  auto bad = [](const std::string& what) { fail(Code::InternalError, Stage::Validate, "halfedge mesh: " + what); };
  const size_t nh = halfedgeCount();
  if (nh % 2 != 0) bad("odd halfedge count");
  size_t boundary = 0;
  std::vector<uint8_t> loopChecked(nh, 0);
  for (HalfedgeId h : halfedges()) {
    std::string hs = "halfedge " + std::to_string(h.idx());
    if (!next(h).valid() || next(h).idx() >= nh || !prev(h).valid() || prev(h).idx() >= nh) bad(hs + " has no next/prev");
    if (prev(next(h)) != h || next(prev(h)) != h) bad(hs + ": next/prev disagree");
    if (twin(twin(h)) != h || twin(h) == h) bad(hs + ": twin");
    if (!tail(h).valid() || tail(h).idx() >= vertexCount()) bad(hs + ": tail out of range");
    if (tail(next(h)) != tip(h)) bad(hs + ": next does not start at tip");
    if (tip(h) == tail(h)) bad(hs + ": loop edge");
    if (face(next(h)) != face(h)) bad(hs + ": next in another face");
    if (isBoundary(h) && isBoundary(twin(h))) bad(hs + ": edge without faces");
    if (isBoundary(h)) {
      ++boundary;
      // A boundary loop is a closed cycle of boundary halfedges (length capped by nh); each
      // loop is walked once.
      if (!loopChecked[h.idx()]) {
        size_t n = 0;
        HalfedgeId g = h;
        do {
          loopChecked[g.idx()] = 1;
          g = next(g);
          ++n;
        } while (g != h && n <= nh);
        if (g != h) bad(hs + ": boundary loop does not close");
      }
    } else {
      if (face(h).idx() >= faceCount()) bad(hs + ": face out of range");
      if (next(next(next(h))) != h) bad(hs + ": face is not a triangle");
    }
    if (h == halfedge(edge(h)) && isBoundary(h)) bad(hs + ": edge's first halfedge is a boundary halfedge");
  }
  if (boundary != boundaryHalfedgeCount_) bad("boundary halfedge count");
  for (FaceId f : faces()) {
    HalfedgeId h = halfedge(f);
    if (!h.valid() || face(h) != f) bad("face " + std::to_string(f.idx()) + ": halfedge not in the face");
  }
  std::vector<uint32_t> outDegree(vertexCount(), 0);
  for (HalfedgeId h : halfedges()) ++outDegree[tail(h).idx()];
  for (VertexId v : vertices()) {
    std::string vs = "vertex " + std::to_string(v.idx());
    HalfedgeId h0 = halfedge(v);
    if (!h0.valid()) {
      if (outDegree[v.idx()] != 0) bad(vs + ": isolated but has halfedges");
      continue;
    }
    if (tail(h0) != v) bad(vs + ": halfedge does not start at it");
    size_t n = 0, nb = 0;
    HalfedgeId h = h0;
    do {
      if (isBoundary(h)) ++nb;
      h = rotateCcw(h);
      ++n;
    } while (h != h0 && n <= nh);
    if (n != outDegree[v.idx()]) bad(vs + ": more than one fan");
    if (nb > 1) bad(vs + ": more than one boundary halfedge");
    if (nb == 1 && !isBoundary(h0)) bad(vs + ": boundary vertex whose halfedge is not the boundary one");
  }
}

}  // namespace conformesh
