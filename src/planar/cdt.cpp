// Constrained Delaunay triangulation of a PSLG; see cdt.h and cdt_state.h.
#include "planar/cdt.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "core/hilbert.h"
#include "core/triangle_corner.h"
#include "planar/cdt_state.h"

namespace conformesh::planar {
namespace {

[[noreturn]] void pslgError(const std::string& msg) { fail(Code::InvalidPslg, Stage::Refine, msg); }

class CdtBuilder {
 public:
  CdtBuilder(CdtState& s, const ProgressFn& progress) : s_(s), T_(s.tri), progress_(progress) {}

  void run(const Pslg& in, const CdtOptions& opt) {
    readInput(in);
    triangulatePoints();
    if (progress_ && !progress_(Stage::Refine, 0.0)) fail(Code::Cancelled, Stage::Refine, "cancelled");
    for (uint32_t sIdx = 0; sIdx < s_.nInputSegments; ++sIdx) {
      insertSegment(s_.segA[sIdx], s_.segB[sIdx], sIdx);
      if (progress_ && (sIdx & 0xFFFF) == 0xFFFF && !progress_(Stage::Refine, 0.0))
        fail(Code::Cancelled, Stage::Refine, "cancelled");
    }
    if (opt.convexHull || s_.nInputSegments == 0) constrainHull();
    classify(in, opt);
    bool any = false;
    for (uint32_t t = 0; t < T_.tris.size() && !any; ++t) any = s_.inDomain(t);
    if (!any)
      pslgError("the domain is empty: no closed segment loop encloses a region (or hole seeds remove "
                "everything); CdtOptions::convexHull meshes the convex hull");
  }

 private:
  CdtState& s_;
  Triangulation& T_;
  const ProgressFn& progress_;
  std::vector<uint32_t> distinct_;

  void readInput(const Pslg& in) {
    if (in.points.size() % 2 || in.segments.size() % 2 || in.holes.size() % 2)
      fail(Code::InvalidArgument, Stage::Refine, "PSLG arrays must have an even number of entries");
    size_t n = in.points.size() / 2;
    if (n >= (size_t(1) << 30)) fail(Code::TooLarge, Stage::Refine, "too many points");
    size_t nseg = in.segments.size() / 2;
    if (!in.segmentMarkers.empty() && in.segmentMarkers.size() != nseg)
      fail(Code::InvalidArgument, Stage::Refine, "segmentMarkers must be empty or one per segment");
    s_.nInput = uint32_t(n);
    T_.xy.reserve(in.points.size());
    for (size_t i = 0; i < n; ++i) {
      double x = in.points[2 * i], y = in.points[2 * i + 1];
      if (!std::isfinite(x) || !std::isfinite(y))
        fail(Code::NonFiniteCoordinate, Stage::Refine, "point " + std::to_string(i) + " is not finite");
      T_.addVertex(x, y);
    }
    for (double h : in.holes)
      if (!std::isfinite(h)) fail(Code::NonFiniteCoordinate, Stage::Refine, "hole seed is not finite");
    // Merge exact duplicates.
    std::vector<uint32_t> idx(n);
    for (uint32_t i = 0; i < n; ++i) idx[i] = i;
    const double* xy = T_.xy.data();
    std::sort(idx.begin(), idx.end(), [xy](uint32_t a, uint32_t b) {
      if (xy[2 * a] != xy[2 * b]) return xy[2 * a] < xy[2 * b];
      if (xy[2 * a + 1] != xy[2 * b + 1]) return xy[2 * a + 1] < xy[2 * b + 1];
      return a < b;
    });
    s_.rep.assign(n, 0);
    for (size_t k = 0; k < n; ++k) {
      uint32_t i = idx[k];
      if (k > 0 && xy[2 * i] == xy[2 * idx[k - 1]] && xy[2 * i + 1] == xy[2 * idx[k - 1] + 1]) {
        s_.rep[i] = s_.rep[idx[k - 1]];
      } else {
        s_.rep[i] = i;
        distinct_.push_back(i);
      }
    }
    s_.vseg.assign(n, -1);
    s_.vparam.assign(n, 0.0);
    s_.segDegree.assign(n, 0);
    s_.nInputSegments = uint32_t(nseg);
    for (size_t k = 0; k < nseg; ++k) {
      uint32_t a = in.segments[2 * k], b = in.segments[2 * k + 1];
      if (a >= n || b >= n)
        fail(Code::IndexOutOfRange, Stage::Refine,
             "segment " + std::to_string(k) + " refers to vertex " + std::to_string(std::max(a, b)) +
                 " of " + std::to_string(n));
      a = s_.rep[a];
      b = s_.rep[b];
      if (a == b) pslgError("segment " + std::to_string(k) + " has coincident endpoints");
      s_.segA.push_back(a);
      s_.segB.push_back(b);
      s_.segMarker.push_back(in.segmentMarkers.empty() ? 0 : in.segmentMarkers[k]);
    }
  }

  void triangulatePoints() {
    if (distinct_.size() < 3) pslgError("fewer than 3 distinct points");
    const std::vector<uint32_t> order = hilbertOrder(T_.pt(0), distinct_);
    T_.buildDelaunay(order);
  }

  double paramOn(uint32_t seg, uint32_t v) const {
    const double* a = T_.pt(s_.segA[seg]);
    const double* b = T_.pt(s_.segB[seg]);
    const double* p = T_.pt(v);
    if (v == s_.segA[seg]) return 0.0;
    if (v == s_.segB[seg]) return 1.0;
    double dx = b[0] - a[0], dy = b[1] - a[1];
    return ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy);
  }

  void constrainSub(uint32_t h, uint32_t a, uint32_t b, uint32_t seg) {
    uint64_t k = CdtState::key(a, b);
    if (T_.isConstrained(hTri(h), hEdge(h))) {
      auto it = s_.subseg.find(k);
      uint32_t other = it == s_.subseg.end() ? seg : it->second;
      bool same = (s_.segA[other] == s_.segA[seg] && s_.segB[other] == s_.segB[seg]) ||
                  (s_.segA[other] == s_.segB[seg] && s_.segB[other] == s_.segA[seg]);
      if (other != seg && !same)
        pslgError("segments " + std::to_string(other) + " and " + std::to_string(seg) + " overlap");
      return;
    }
    T_.setEdgeConstrained(h, true);
    s_.subseg[k] = seg;
    ++s_.segDegree[a];
    ++s_.segDegree[b];
    for (uint32_t v : {a, b}) {
      if (s_.vseg[v] < 0) {
        s_.vseg[v] = int32_t(seg);
        s_.vparam[v] = paramOn(seg, v);
      }
    }
  }

  [[noreturn]] void crossing(uint32_t x, uint32_t y, uint32_t seg) {
    int32_t other = s_.segmentOf(x, y);
    pslgError("segments " + std::to_string(other) + " and " + std::to_string(seg) + " cross");
  }

  void insertSegment(uint32_t a, uint32_t b, uint32_t seg) {
    const size_t cap = size_t(T_.vertexCount()) + 8;
    for (size_t guard = 0; guard < cap && a != b; ++guard) {
      uint32_t h = T_.findEdge(a, b);
      if (h != kNone) {
        constrainSub(h, a, b, seg);
        return;
      }
      // The triangle around a whose wedge contains the direction to b.
      const double* pa = T_.pt(a);
      const double* pb = T_.pt(b);
      uint32_t t = T_.vtri[a], start = t, found = kNone, through = kNone;
      for (size_t g2 = 0; g2 < T_.tris.size() + 4; ++g2) {
        const Tri& Tt = T_.tris[t];
        const uint32_t i = uint32_t(cornerOf(Tt.v, a));
        if (!T_.isGhost(t)) {
          uint32_t x = Tt.v[nxt(i)], y = Tt.v[prv(i)];
          double o1 = orient2d(pa, T_.pt(x), pb), o2 = orient2d(pa, T_.pt(y), pb);
          auto ahead = [&](uint32_t w) {
            const double* pw = T_.pt(w);
            return (pw[0] - pa[0]) * (pb[0] - pa[0]) + (pw[1] - pa[1]) * (pb[1] - pa[1]) > 0;
          };
          if (o1 == 0 && ahead(x)) {
            through = x;
            found = mkH(t, prv(i));
            break;
          }
          if (o2 == 0 && ahead(y)) {
            through = y;
            found = mkH(t, nxt(i));
            break;
          }
          if (o1 > 0 && o2 < 0) {
            found = mkH(t, i);
            break;
          }
        }
        t = hTri(Tt.n[nxt(i)]);
        if (t == start) break;
      }
      if (found == kNone)
        fail(Code::InternalError, Stage::Refine, "segment insertion: no triangle around the endpoint");
      if (through != kNone) {  // a vertex lies on the segment: constrain up to it, go on from it
        constrainSub(found, a, through, seg);
        a = through;
        continue;
      }
      a = walkAndRetriangulate(found, a, b, seg);
    }
  }

  std::vector<uint32_t> crossed_, left_, right_;
  struct HalfEdgeKey {
    uint64_t key;
    uint32_t handle;
    uint8_t con;
  };
  std::vector<HalfEdgeKey> keys_;
  std::vector<std::array<uint32_t, 3>> newTris_;

  // Removes the triangles crossed by segment a-b (starting with edge `h` opposite a), and
  // retriangulates both sides. Returns the vertex where the constrained piece ends (b, or a
  // vertex exactly on the segment).
  uint32_t walkAndRetriangulate(uint32_t h, uint32_t a, uint32_t b, uint32_t seg) {
    crossed_.clear();
    left_.clear();
    right_.clear();
    uint32_t cur = hTri(h), e = hEdge(h);
    crossed_.push_back(cur);
    uint32_t x = T_.tris[cur].v[nxt(e)], y = T_.tris[cur].v[prv(e)];
    right_.push_back(x);
    left_.push_back(y);
    const double* pa = T_.pt(a);
    const double* pb = T_.pt(b);
    uint32_t end = kNone;
    for (size_t guard = 0; guard < T_.tris.size() + 4; ++guard) {
      if (T_.isConstrained(cur, e)) crossing(x, y, seg);
      uint32_t nh = T_.tris[cur].n[e];
      uint32_t nt = hTri(nh), ne = hEdge(nh);
      if (T_.isGhost(nt)) fail(Code::InternalError, Stage::Refine, "segment insertion left the hull");
      crossed_.push_back(nt);
      uint32_t z = T_.tris[nt].v[ne];
      if (z == b) {
        end = b;
        break;
      }
      double o = orient2d(pa, pb, T_.pt(z));
      if (o == 0) {
        end = z;
        break;
      }
      if (o < 0) {
        right_.push_back(z);
        x = z;
        e = prv(ne);
      } else {
        left_.push_back(z);
        y = z;
        e = nxt(ne);
      }
      cur = nt;
    }
    if (end == kNone) fail(Code::InternalError, Stage::Refine, "segment insertion walk did not end");
    // Cavity boundary.
    keys_.clear();
    for (uint32_t t : crossed_) T_.tf[t] |= kMark;
    uint8_t outsideFlag = 0;
    for (uint32_t t : crossed_) {
      const Tri& Tt = T_.tris[t];
      for (uint32_t i = 0; i < 3; ++i) {
        uint32_t nb = hTri(Tt.n[i]);
        if (T_.tf[nb] & kMark) continue;
        keys_.push_back({CdtState::key(Tt.v[nxt(i)], Tt.v[prv(i)]), Tt.n[i], uint8_t(T_.isConstrained(t, i))});
      }
    }
    (void)outsideFlag;
    // New triangles: both pseudo-polygons.
    newTris_.clear();
    triangulatePseudo(a, end, left_);
    std::reverse(right_.begin(), right_.end());
    triangulatePseudo(end, a, right_);
    if (newTris_.size() != crossed_.size())
      fail(Code::InternalError, Stage::Refine, "segment insertion: cavity count mismatch");
    for (size_t k = 0; k < newTris_.size(); ++k) {
      uint32_t t = crossed_[k];
      T_.tf[t] = 0;
      Tri& Tt = T_.tris[t];
      for (int j = 0; j < 3; ++j) Tt.v[j] = newTris_[k][j];
      for (uint32_t i = 0; i < 3; ++i)
        keys_.push_back({CdtState::key(Tt.v[nxt(i)], Tt.v[prv(i)]), mkH(t, i), 2});
      for (int j = 0; j < 3; ++j) T_.vtri[Tt.v[j]] = t;
    }
    std::sort(keys_.begin(), keys_.end(), [](const HalfEdgeKey& p, const HalfEdgeKey& q) {
      return p.key < q.key || (p.key == q.key && p.con < q.con);
    });
    for (size_t k = 0; k + 1 < keys_.size(); k += 2) {
      if (keys_[k].key != keys_[k + 1].key)
        fail(Code::InternalError, Stage::Refine, "segment insertion: unmatched cavity edge");
      T_.link(keys_[k].handle, keys_[k + 1].handle);
      if (keys_[k].con == 1) T_.setConstrained(hTri(keys_[k + 1].handle), hEdge(keys_[k + 1].handle), true);
    }
    uint32_t hab = T_.findEdge(a, end);
    if (hab == kNone) fail(Code::InternalError, Stage::Refine, "segment insertion: edge missing");
    constrainSub(hab, a, end, seg);
    return end;
  }

  // CDT of the pseudo-polygon u -> w -> c[k-1] ... c[0] (chain on the left of u -> w).
  void triangulatePseudo(uint32_t u, uint32_t w, const std::vector<uint32_t>& c) {
    struct Job {
      uint32_t u, w;
      size_t lo, hi;
    };
    std::vector<Job> jobs{{u, w, 0, c.size()}};
    while (!jobs.empty()) {
      Job j = jobs.back();
      jobs.pop_back();
      if (j.lo >= j.hi) continue;
      size_t m = j.lo;
      for (size_t k = j.lo + 1; k < j.hi; ++k)
        if (incircle(T_.pt(j.u), T_.pt(j.w), T_.pt(c[m]), T_.pt(c[k])) > 0) m = k;
      newTris_.push_back({j.u, j.w, c[m]});
      jobs.push_back({j.u, c[m], j.lo, m});
      jobs.push_back({c[m], j.w, m + 1, j.hi});
    }
  }

  void constrainHull() {
    size_t nt = T_.tris.size();
    for (uint32_t t = 0; t < nt; ++t) {
      if (!(T_.tf[t] & kIsGhost) || (T_.tf[t] & kDead)) continue;
      const Tri& Tt = T_.tris[t];
      uint32_t k = Tt.v[0] == kGhost ? 0 : (Tt.v[1] == kGhost ? 1 : 2);
      if (T_.isConstrained(t, k)) continue;
      uint32_t a = Tt.v[nxt(k)], b = Tt.v[prv(k)];
      uint32_t seg = uint32_t(s_.segA.size());
      s_.segA.push_back(b);  // the domain side runs b -> a (counter-clockwise hull)
      s_.segB.push_back(a);
      s_.segMarker.push_back(1);
      constrainSub(mkH(t, k), a, b, seg);
    }
  }

  void classify(const Pslg& in, const CdtOptions& opt) {
    const size_t nt = T_.tris.size();
    std::vector<uint32_t> queue;
    if (!opt.holesByOrientation) {
      for (uint32_t t = 0; t < nt; ++t) {
        if ((T_.tf[t] & kDead) || !(T_.tf[t] & kIsGhost)) continue;
        T_.tf[t] |= kOutside;
        const Tri& Tt = T_.tris[t];
        uint32_t k = Tt.v[0] == kGhost ? 0 : (Tt.v[1] == kGhost ? 1 : 2);
        uint32_t nb = hTri(Tt.n[k]);
        if (!T_.isConstrained(t, k) && !(T_.tf[nb] & kOutside)) {
          T_.tf[nb] |= kOutside;
          queue.push_back(nb);
        }
      }
    } else {
      orientationClassify();
    }
    uint32_t start = T_.vtri[distinct_[0]];
    for (size_t k = 0; k + 1 < in.holes.size(); k += 2) {
      double p[2] = {in.holes[k], in.holes[k + 1]};
      uint32_t t = T_.locate(p, start);
      if (T_.isGhost(t) || (T_.tf[t] & kOutside)) continue;
      T_.tf[t] |= kOutside;
      queue.push_back(t);
    }
    while (!queue.empty()) {
      uint32_t t = queue.back();
      queue.pop_back();
      for (uint32_t i = 0; i < 3; ++i) {
        if (T_.isConstrained(t, i)) continue;
        uint32_t nb = hTri(T_.tris[t].n[i]);
        if (T_.tf[nb] & kOutside) continue;
        T_.tf[nb] |= kOutside;
        queue.push_back(nb);
      }
    }
  }

  // Winding numbers by breadth-first search from the ghost triangles (winding 0).
  void orientationClassify() {
    const size_t nt = T_.tris.size();
    const size_t nseg = s_.segA.size();
    std::vector<int32_t> balance(s_.nInput, 0);
    for (size_t k = 0; k < nseg; ++k) {
      ++balance[s_.segA[k]];
      --balance[s_.segB[k]];
    }
    std::vector<uint8_t> loopSeg(nseg);
    for (size_t k = 0; k < nseg; ++k) loopSeg[k] = balance[s_.segA[k]] == 0 && balance[s_.segB[k]] == 0;
    const int32_t kUnset = INT32_MIN;
    std::vector<int32_t> wind(nt, kUnset);
    std::vector<uint32_t> queue;
    for (uint32_t t = 0; t < nt; ++t) {
      if ((T_.tf[t] & kDead) || !(T_.tf[t] & kIsGhost)) continue;
      wind[t] = 0;
      queue.push_back(t);
    }
    for (size_t qi = 0; qi < queue.size(); ++qi) {
      uint32_t t = queue[qi];
      const Tri& Tt = T_.tris[t];
      for (uint32_t i = 0; i < 3; ++i) {
        uint32_t nb = hTri(Tt.n[i]);
        int32_t w = wind[t];
        uint32_t u = Tt.v[nxt(i)], v = Tt.v[prv(i)];
        if (T_.isConstrained(t, i) && u != kGhost && v != kGhost) {
          int32_t seg = s_.segmentOf(u, v);
          if (seg >= 0 && loopSeg[size_t(seg)]) {
            const double* A = T_.pt(s_.segA[size_t(seg)]);
            const double* B = T_.pt(s_.segB[size_t(seg)]);
            const double* pu = T_.pt(u);
            const double* pv = T_.pt(v);
            bool forward = (pv[0] - pu[0]) * (B[0] - A[0]) + (pv[1] - pu[1]) * (B[1] - A[1]) > 0;
            w += forward ? -1 : 1;  // t lies left of u -> v
          }
        }
        if (wind[nb] == kUnset) {
          wind[nb] = w;
          queue.push_back(nb);
        } else if (wind[nb] != w) {
          pslgError("segment loops are not consistently oriented (holesByOrientation)");
        }
      }
    }
    for (uint32_t t = 0; t < nt; ++t)
      if (!(T_.tf[t] & kDead) && (wind[t] == 0 || (T_.tf[t] & kIsGhost))) T_.tf[t] |= kOutside;
  }
};

}  // namespace

void buildCdt(const Pslg& pslg, const CdtOptions& options, const ProgressFn& progress, CdtState& s) {
  CdtBuilder b(s, progress);
  b.run(pslg, options);
}

void extractMesh(CdtState& s, PlanarMesh& out, bool consume) {
  Triangulation& T = s.tri;
  const uint32_t nv = T.vertexCount();
  out = PlanarMesh{};
  size_t domainTris = 0;
  for (uint32_t t = 0; t < T.tris.size(); ++t) domainTris += s.inDomain(t);
  out.triangles.reserve(3 * domainTris);
  for (uint32_t t = 0; t < T.tris.size(); ++t) {
    if (!s.inDomain(t)) continue;
    const Tri& Tt = T.tris[t];
    out.triangles.insert(out.triangles.end(), {Tt.v[0], Tt.v[1], Tt.v[2]});
    for (uint32_t i = 0; i < 3; ++i) {
      if (!T.isConstrained(t, i)) continue;
      uint32_t nb = hTri(Tt.n[i]);
      if (s.inDomain(nb) && nb < t) continue;
      uint32_t u = Tt.v[nxt(i)], v = Tt.v[prv(i)];
      out.edges.push_back(u);
      out.edges.push_back(v);
      int32_t seg = s.segmentOf(u, v);
      bool hull = seg >= 0 && uint32_t(seg) >= s.nInputSegments;
      out.edgeSegment.push_back(hull ? -1 : seg);
      out.edgeMarker.push_back(seg >= 0 ? s.segMarker[size_t(seg)] : 0);
    }
  }
  if (consume) {
    std::vector<Tri>().swap(T.tris);  // release before the vertex arrays are handed over
    std::vector<uint8_t>().swap(T.tf);
    out.points = std::move(T.xy);
    out.vertexSegment = std::move(s.vseg);
    out.vertexParam = std::move(s.vparam);
  } else {
    out.points = T.xy;
    out.vertexSegment = s.vseg;
    out.vertexParam = s.vparam;
  }
  out.vertexSegment.resize(nv, -1);
  out.vertexParam.resize(nv, 0.0);
  for (uint32_t i = 0; i < s.nInput; ++i) {
    if (s.rep[i] != i) {
      out.vertexSegment[i] = out.vertexSegment[s.rep[i]];
      out.vertexParam[i] = out.vertexParam[s.rep[i]];
    }
  }
  for (uint32_t i = 0; i < nv; ++i)
    if (out.vertexSegment[i] >= 0 && uint32_t(out.vertexSegment[i]) >= s.nInputSegments) {
      out.vertexSegment[i] = -1;
      out.vertexParam[i] = 0.0;
    }
}

PlanarMesh triangulatePslg(const Pslg& pslg, const CdtOptions& options, const ProgressFn& progress) {
  CdtState s;
  buildCdt(pslg, options, progress, s);
  PlanarMesh out;
  extractMesh(s, out);
  return out;
}

}  // namespace conformesh::planar
