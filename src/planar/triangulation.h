// conformesh — the planar triangulation data structure behind the CDT and the refinement
// (internal header of src/planar; the public entry points are cdt.h and refine.h).
//
// Compact, index-based: a triangle is 3 vertex ids and 3 neighbour handles (24 bytes) plus one
// flag byte; a neighbour handle is (triangle << 2) | edge, edge i being the edge opposite
// vertex i, i.e. v[i+1] -> v[i+2]. The triangulation always covers the whole plane: the convex
// hull is closed by "ghost" triangles that share the infinite vertex kGhost, so every
// adjacency is defined and insertion outside the hull needs no special case. Triangles
// outside the meshing domain (holes, concavities) stay in the structure with kOutside set;
// every edge between domain and non-domain is constrained, so refinement never enters them.
//
// Point insertion is Bowyer–Watson (cavity of triangles whose circumcircle contains the point,
// not crossing constrained edges, then a fan), with exact predicates (predicates.h).
// Segment insertion removes the crossed triangles and retriangulates the two pseudo-polygons
// (Anglada 1997, "An improved incremental algorithm for constructing restricted Delaunay
// triangulations").
#pragma once

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "planar/predicates.h"

namespace conformesh::planar {

constexpr uint32_t kNone = 0xFFFFFFFFu;
constexpr uint32_t kGhost = 0xFFFFFFFEu;

struct Tri {
  uint32_t v[3];
  uint32_t n[3];
};

enum TriFlag : uint8_t {
  kCon0 = 1,  // edge 0 constrained (bits 0..2: edges 0..2)
  kDead = 8,
  kOutside = 16,
  kMark = 32,
  kIsGhost = 64,
};

inline uint32_t hTri(uint32_t h) { return h >> 2; }
inline uint32_t hEdge(uint32_t h) { return h & 3u; }
inline uint32_t mkH(uint32_t t, uint32_t e) { return (t << 2) | e; }
inline uint32_t nxt(uint32_t i) { return i == 2 ? 0 : i + 1; }
inline uint32_t prv(uint32_t i) { return i == 0 ? 2 : i - 1; }

//! One edge of a cavity boundary, oriented as in the cavity triangle that owns it.
struct CavityEdge {
  uint32_t u, v;
  uint32_t outer;    // handle of the same edge in the triangle outside the cavity
  uint8_t flags;     // bit 0: constrained; bit 4: the owning cavity triangle was kOutside
};

class Triangulation {
 public:
  std::vector<double> xy;      // 2 per vertex
  std::vector<Tri> tris;
  std::vector<uint8_t> tf;     // TriFlag bits per triangle
  std::vector<uint32_t> vtri;  // per vertex: one incident triangle (kNone before insertion)
  std::vector<uint32_t> freeTris;

  // Scratch of the last findCavity / commitCavity.
  std::vector<uint32_t> cavity;
  std::vector<CavityEdge> boundary;
  std::vector<uint32_t> fan;  // triangles created by the last commit

  const double* pt(uint32_t v) const { return &xy[2 * size_t(v)]; }
  uint32_t vertexCount() const { return uint32_t(xy.size() / 2); }
  bool isGhost(uint32_t t) const { return (tf[t] & kIsGhost) != 0; }
  bool isConstrained(uint32_t t, uint32_t e) const { return (tf[t] >> e) & 1u; }
  void setConstrained(uint32_t t, uint32_t e, bool on);
  //! Constrain (or release) an edge on both of its sides.
  void setEdgeConstrained(uint32_t h, bool on);

  //! Append a vertex (not yet inserted into the triangulation); returns its id.
  uint32_t addVertex(double x, double y);

  //! Delaunay triangulation of all vertices currently in xy (exact duplicates must have been
  //! removed by the caller: `order` lists the distinct vertices to insert). Throws
  //! InvalidPslg if all points are collinear. Progress: callback per 64k points.
  void buildDelaunay(const std::vector<uint32_t>& order);

  //! Ghost-aware conflict test: is p strictly inside the circumcircle of t (or, for a ghost
  //! triangle, strictly in its open half-plane or on the interior of its hull edge)?
  bool inConflict(uint32_t t, const double* p) const;

  //! Walk from triangle `start` to a triangle that contains p (closed) or, if p is outside the
  //! hull, a ghost triangle in conflict with p. Constraints are ignored.
  uint32_t locate(const double* p, uint32_t start) const;

  //! Collect the cavity of p starting at t0 (which must conflict with p or contain it). If
  //! splitEdge != kNone (a handle of an edge of t0 on which p lies), the triangle across it is
  //! part of the cavity too and the edge itself may be constrained. Marks cavity triangles
  //! with kMark; call commitCavity or clearCavity next. Returns false if the cavity is not
  //! star-shaped from p (possible only next to constraints); then call clearCavity.
  bool findCavity(const double* p, uint32_t t0, uint32_t splitEdge);
  void clearCavity();
  //! Replace the cavity by the fan around vertex p; if the cavity was opened on a constrained
  //! split edge (a, b), the edges (p, a), (p, b) become constrained. Fills `fan`.
  void commitCavity(uint32_t p, uint32_t splitA = kNone, uint32_t splitB = kNone);

  //! Handle of the edge u -> v in the triangle to its left, or kNone if u, v are not joined.
  uint32_t findEdge(uint32_t u, uint32_t v) const;

  uint32_t newTri();
  void freeTri(uint32_t t);
  void link(uint32_t h1, uint32_t h2) {
    tris[hTri(h1)].n[hEdge(h1)] = h2;
    tris[hTri(h2)].n[hEdge(h2)] = h1;
  }

 private:
  std::vector<uint32_t> stack_;
  std::vector<uint32_t> fanStart_;  // per vertex scratch
  uint32_t ghostStart_ = kNone;
};

}  // namespace conformesh::planar
