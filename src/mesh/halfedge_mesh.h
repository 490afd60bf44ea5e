// conformesh — halfedge mesh with typed index handles.
//
// Layout (compact arrays, every query O(1)):
//   * halfedges come in pairs: twin(h) = h ^ 1, edge(h) = h / 2, halfedge(e) = 2e;
//   * next, prev, tail vertex and face are stored per halfedge;
//   * a boundary halfedge is a real halfedge with no face (face(h) invalid); boundary halfedges
//     are linked by next/prev into closed loops that run clockwise around each hole seen from
//     the outside (opposite to the interior faces' counter-clockwise order);
//   * face f is triangle f of the MeshBuffers it was built from, and halfedge(f) goes from
//     triangles[3f] to triangles[3f+1] (then next: [3f+1]->[3f+2], [3f+2]->[3f]);
//   * vertex v is vertex v of the buffers; halfedge(v) is an outgoing halfedge, and for a vertex
//     on the boundary it is the outgoing boundary halfedge (so isBoundary(v) is O(1)). A vertex
//     that no face uses is isolated: halfedge(v) invalid.
// The mesh is always an oriented 2-manifold with boundary: fromTriangles() rejects anything else
// (use validate() in mesh/validate.h first to repair what can be repaired).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <type_traits>
#include <vector>

#include "core/status.h"

namespace conformesh {

//! An index handle of one element kind. Handles of different kinds are distinct types, so a
//! VertexId cannot be passed where a FaceId is expected, nor used to index FaceData.
template <class Tag>
class Handle {
 public:
  using Index = uint32_t;
  static constexpr Index kInvalid = 0xffffffffu;

  constexpr Handle() = default;
  template <class I, class = std::enable_if_t<std::is_integral<I>::value>>
  constexpr explicit Handle(I i) : idx_(Index(i)) {}

  constexpr Index idx() const { return idx_; }
  constexpr bool valid() const { return idx_ != kInvalid; }
  static constexpr Handle invalid() { return Handle(); }

  constexpr bool operator==(Handle o) const { return idx_ == o.idx_; }
  constexpr bool operator!=(Handle o) const { return idx_ != o.idx_; }
  constexpr bool operator<(Handle o) const { return idx_ < o.idx_; }

 private:
  Index idx_ = kInvalid;
};

struct VertexTag {};
struct HalfedgeTag {};
struct EdgeTag {};
struct FaceTag {};
using VertexId = Handle<VertexTag>;
using HalfedgeId = Handle<HalfedgeTag>;
using EdgeId = Handle<EdgeTag>;
using FaceId = Handle<FaceTag>;

class HalfedgeMesh;
namespace detail {
struct EdgeGroups;
}

//! Per-element data indexed by one handle kind (VertexData<double>, FaceData<int>, ...).
//! A plain std::vector inside; data() exposes it for bulk work.
template <class H, class T>
class MeshData {
 public:
  MeshData() = default;
  explicit MeshData(size_t n, const T& value = T()) : data_(n, value) {}
  //! Sized for `mesh`'s elements of kind H (defined after HalfedgeMesh).
  explicit MeshData(const HalfedgeMesh& mesh, const T& value = T());

  typename std::vector<T>::reference operator[](H h) { return data_[h.idx()]; }
  typename std::vector<T>::const_reference operator[](H h) const { return data_[h.idx()]; }
  size_t size() const { return data_.size(); }
  void fill(const T& value) { std::fill(data_.begin(), data_.end(), value); }
  std::vector<T>& data() { return data_; }
  const std::vector<T>& data() const { return data_; }

 private:
  std::vector<T> data_;
};

template <class T>
using VertexData = MeshData<VertexId, T>;
template <class T>
using HalfedgeData = MeshData<HalfedgeId, T>;
template <class T>
using EdgeData = MeshData<EdgeId, T>;
template <class T>
using FaceData = MeshData<FaceId, T>;

//! The range of all handles 0..n-1 of one kind: `for (VertexId v : mesh.vertices())`.
template <class H>
class HandleRange {
 public:
  class iterator {
   public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = H;
    using difference_type = std::ptrdiff_t;
    using pointer = const H*;
    using reference = H;
    explicit iterator(uint32_t i) : i_(i) {}
    H operator*() const { return H(i_); }
    iterator& operator++() {
      ++i_;
      return *this;
    }
    bool operator==(const iterator& o) const { return i_ == o.i_; }
    bool operator!=(const iterator& o) const { return i_ != o.i_; }

   private:
    uint32_t i_;
  };
  explicit HandleRange(size_t n) : n_(uint32_t(n)) {}
  iterator begin() const { return iterator(0); }
  iterator end() const { return iterator(n_); }
  size_t size() const { return n_; }

 private:
  uint32_t n_;
};

//! Halfedges visited by repeatedly applying a step (e.g. rotation around a vertex) until the
//! first one comes back. Valid meshes guarantee termination (the cycles are closed).
template <class Step, class Out>
class HalfedgeCycle {
 public:
  class iterator {
   public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = Out;
    using difference_type = std::ptrdiff_t;
    using pointer = const Out*;
    using reference = Out;
    iterator(const HalfedgeMesh* m, HalfedgeId h, bool done) : m_(m), start_(h), h_(h), done_(done) {}
    Out operator*() const { return Step::out(*m_, h_); }
    iterator& operator++() {
      h_ = Step::step(*m_, h_);
      if (h_ == start_) done_ = true;
      return *this;
    }
    bool operator==(const iterator& o) const { return done_ == o.done_ && (done_ || h_ == o.h_); }
    bool operator!=(const iterator& o) const { return !(*this == o); }

   private:
    const HalfedgeMesh* m_;
    HalfedgeId start_, h_;
    bool done_;
  };
  HalfedgeCycle(const HalfedgeMesh* m, HalfedgeId start) : m_(m), start_(start) {}
  iterator begin() const { return iterator(m_, start_, !start_.valid()); }
  iterator end() const { return iterator(m_, start_, true); }

 private:
  const HalfedgeMesh* m_;
  HalfedgeId start_;
};

//! A triangle mesh as halfedges: an oriented 2-manifold, possibly with boundary, possibly with
//! several components. Connectivity only; positions live in VertexData<Vec3> beside it.
class HalfedgeMesh {
 public:
  HalfedgeMesh() = default;

  //! Build from flat triangles (3·nF vertex indices, counter-clockwise) over `vertexCount`
  //! vertices. Edges are matched by bucketing halfedges by their smaller vertex (counting sort)
  //! and sorting each bucket: O(nF log d), d the largest vertex degree.
  //! \throw Error(stage Validate): IndexOutOfRange (an index >= vertexCount), DegenerateFace (a
  //!   triangle repeats a vertex), NonManifoldEdge (an edge in more than two triangles),
  //!   InconsistentOrientation (two triangles traverse their shared edge the same way),
  //!   NonManifoldVertex (a vertex whose triangles form more than one fan), TooLarge (more than
  //!   2^31 halfedges). Messages name the offending vertices / triangles.
  static HalfedgeMesh fromTriangles(size_t vertexCount, const std::vector<uint32_t>& triangles);
  //! As fromTriangles, with the corners already grouped by undirected edge (mesh/edge_groups.h;
  //! used by validate(), which groups them for its own checks). Same checks and errors.
  static HalfedgeMesh fromGroupedTriangles(size_t vertexCount, const std::vector<uint32_t>& triangles,
                                           detail::EdgeGroups&& groups);

  // ---- counts and ranges -------------------------------------------------------------------
  size_t vertexCount() const { return vertexHalfedge_.size(); }
  size_t halfedgeCount() const { return next_.size(); }
  size_t edgeCount() const { return next_.size() / 2; }
  size_t faceCount() const { return faceHalfedge_.size(); }
  size_t boundaryHalfedgeCount() const { return boundaryHalfedgeCount_; }

  HandleRange<VertexId> vertices() const { return HandleRange<VertexId>(vertexCount()); }
  HandleRange<HalfedgeId> halfedges() const { return HandleRange<HalfedgeId>(halfedgeCount()); }
  HandleRange<EdgeId> edges() const { return HandleRange<EdgeId>(edgeCount()); }
  HandleRange<FaceId> faces() const { return HandleRange<FaceId>(faceCount()); }

  // ---- halfedge queries (all O(1)) ------------------------------------------------------------
  HalfedgeId twin(HalfedgeId h) const { return HalfedgeId(h.idx() ^ 1u); }
  HalfedgeId next(HalfedgeId h) const { return next_[h.idx()]; }
  HalfedgeId prev(HalfedgeId h) const { return prev_[h.idx()]; }
  //! The vertex h starts at.
  VertexId tail(HalfedgeId h) const { return tail_[h.idx()]; }
  //! The vertex h points to.
  VertexId tip(HalfedgeId h) const { return tail_[h.idx() ^ 1u]; }
  //! The face on h's left; invalid for a boundary halfedge.
  FaceId face(HalfedgeId h) const { return face_[h.idx()]; }
  EdgeId edge(HalfedgeId h) const { return EdgeId(h.idx() >> 1); }
  bool isBoundary(HalfedgeId h) const { return !face_[h.idx()].valid(); }

  // ---- edge, vertex, face queries -------------------------------------------------------------
  //! halfedge(e) is the edge's first halfedge (2e); it always has a face.
  HalfedgeId halfedge(EdgeId e) const { return HalfedgeId(e.idx() << 1); }
  bool isBoundary(EdgeId e) const { return isBoundary(halfedge(e)) || isBoundary(twin(halfedge(e))); }
  //! An outgoing halfedge; the boundary one for a boundary vertex; invalid if isolated.
  HalfedgeId halfedge(VertexId v) const { return vertexHalfedge_[v.idx()]; }
  bool isBoundary(VertexId v) const {
    HalfedgeId h = halfedge(v);
    return h.valid() && isBoundary(h);
  }
  bool isIsolated(VertexId v) const { return !halfedge(v).valid(); }
  //! Halfedge from triangles[3f] to triangles[3f+1].
  HalfedgeId halfedge(FaceId f) const { return faceHalfedge_[f.idx()]; }
  std::array<VertexId, 3> faceVertices(FaceId f) const {
    HalfedgeId h = halfedge(f);
    return {tail(h), tail(next(h)), tail(prev(h))};
  }
  //! Number of edges at v (for a boundary vertex: faces + 1).
  size_t degree(VertexId v) const;
  //! The halfedge from a to b, or invalid if they are not joined by an edge. O(degree(a)).
  HalfedgeId findHalfedge(VertexId a, VertexId b) const;

  // ---- rotation around a vertex ----------------------------------------------------------------
  //! Next outgoing halfedge counter-clockwise around tail(h): twin(prev(h)).
  HalfedgeId rotateCcw(HalfedgeId h) const { return twin(prev(h)); }
  //! Next outgoing halfedge clockwise around tail(h): next(twin(h)).
  HalfedgeId rotateCw(HalfedgeId h) const { return next(twin(h)); }

  // ---- circulators (range-for) ------------------------------------------------------------------
  struct OutgoingStep {
    static HalfedgeId step(const HalfedgeMesh& m, HalfedgeId h) { return m.rotateCcw(h); }
    static HalfedgeId out(const HalfedgeMesh&, HalfedgeId h) { return h; }
  };
  struct NeighborStep {
    static HalfedgeId step(const HalfedgeMesh& m, HalfedgeId h) { return m.rotateCcw(h); }
    static VertexId out(const HalfedgeMesh& m, HalfedgeId h) { return m.tip(h); }
  };
  struct FaceStep {
    static HalfedgeId step(const HalfedgeMesh& m, HalfedgeId h) { return m.next(h); }
    static HalfedgeId out(const HalfedgeMesh&, HalfedgeId h) { return h; }
  };
  //! Outgoing halfedges of v, counter-clockwise, starting at halfedge(v) (boundary one first).
  HalfedgeCycle<OutgoingStep, HalfedgeId> outgoingHalfedges(VertexId v) const { return {this, halfedge(v)}; }
  //! Neighbouring vertices of v, counter-clockwise.
  HalfedgeCycle<NeighborStep, VertexId> vertexNeighbors(VertexId v) const { return {this, halfedge(v)}; }
  //! The three halfedges of f (or the halfedges of a boundary loop, given one boundary halfedge).
  HalfedgeCycle<FaceStep, HalfedgeId> faceHalfedges(FaceId f) const { return {this, halfedge(f)}; }
  HalfedgeCycle<FaceStep, HalfedgeId> loopHalfedges(HalfedgeId h) const { return {this, h}; }
  //! Faces around v, counter-clockwise (the boundary gap skipped).
  std::vector<FaceId> vertexFaces(VertexId v) const;

  //! The triangles as flat indices (3·nF), in face order: the inverse of fromTriangles.
  std::vector<uint32_t> toTriangles() const;

  //! Check every invariant (twin/next/prev/face/tail consistency, triangles, closed boundary
  //! loops, one fan per vertex). Throws Error(InternalError) naming the first violation. O(n).
  void checkInvariants() const;

 private:
  std::vector<HalfedgeId> next_, prev_;
  std::vector<VertexId> tail_;
  std::vector<FaceId> face_;
  std::vector<HalfedgeId> vertexHalfedge_;
  std::vector<HalfedgeId> faceHalfedge_;
  size_t boundaryHalfedgeCount_ = 0;
};

namespace detail {
template <class H>
size_t elementCount(const HalfedgeMesh& m);
template <>
inline size_t elementCount<VertexId>(const HalfedgeMesh& m) { return m.vertexCount(); }
template <>
inline size_t elementCount<HalfedgeId>(const HalfedgeMesh& m) { return m.halfedgeCount(); }
template <>
inline size_t elementCount<EdgeId>(const HalfedgeMesh& m) { return m.edgeCount(); }
template <>
inline size_t elementCount<FaceId>(const HalfedgeMesh& m) { return m.faceCount(); }
}  // namespace detail

template <class H, class T>
MeshData<H, T>::MeshData(const HalfedgeMesh& mesh, const T& value)
    : data_(detail::elementCount<H>(mesh), value) {}

}  // namespace conformesh
