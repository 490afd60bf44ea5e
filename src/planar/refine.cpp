// Planar Delaunay refinement; see refine.h.
#include "planar/refine.h"
#include "core/constants.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <unordered_set>

#include "planar/cdt_state.h"
#include "core/detmath.h"

namespace conformesh::planar {
namespace {


struct BadEntry {
  uint32_t t, a, b, c;
};

// FIFO ring buffer of bad-triangle entries (no per-element allocation, no front erase).
class Ring {
 public:
  bool empty() const { return head_ == tail_; }
  size_t size() const { return tail_ - head_; }
  void push(const BadEntry& e) {
    if (tail_ - head_ == buf_.size()) grow();
    buf_[tail_ & (buf_.size() - 1)] = e;
    ++tail_;
  }
  BadEntry pop() { return buf_[head_++ & (buf_.size() - 1)]; }

 private:
  void grow() {
    std::vector<BadEntry> nb(buf_.empty() ? 256 : 2 * buf_.size());
    for (size_t k = head_; k < tail_; ++k) nb[k - head_] = buf_[k & (buf_.size() - 1)];
    tail_ -= head_;
    head_ = 0;
    buf_.swap(nb);
  }
  std::vector<BadEntry> buf_;
  size_t head_ = 0, tail_ = 0;
};

// Bucketed priority queue of bad triangles: lowest bucket first, FIFO inside a bucket.
class BadQueue {
 public:
  static constexpr int kBuckets = 256;
  void push(int bucket, const BadEntry& e) {
    q_[bucket].push(e);
    if (bucket < lowest_) lowest_ = bucket;
    ++count_;
  }
  bool pop(BadEntry& e) {
    while (lowest_ < kBuckets) {
      if (!q_[lowest_].empty()) {
        e = q_[lowest_].pop();
        --count_;
        return true;
      }
      ++lowest_;
    }
    return false;
  }
  size_t size() const { return count_; }

 private:
  Ring q_[kBuckets];
  int lowest_ = kBuckets;
  size_t count_ = 0;
};

class Refiner {
 public:
  Refiner(CdtState& s, const RefineOptions& o) : s_(s), T_(s.tri), o_(o) {
    double th = o.minAngleDeg * kPi / 180.0;
    angleOn_ = o.minAngleDeg > 0;
    // A hair above θ, so that a triangle that is at θ up to rounding is split rather than
    // reported as 29.999999999999993 degrees.
    cos2Bound_ = dmath::cos(th) * dmath::cos(th) * (1.0 - 1e-9);
    lensCos2_ = angleOn_ && o.diametralLens ? dmath::cos(2 * th) * dmath::cos(2 * th) : 0.0;
    sin2Bound_ = dmath::sin(th) * dmath::sin(th);
    const double ths = o.segmentTriangleMinAngleDeg * kPi / 180.0;
    segBoundOn_ = angleOn_ && o.segmentTriangleMinAngleDeg > o.minAngleDeg;
    cos2SegBound_ = segBoundOn_ ? dmath::cos(ths) * dmath::cos(ths) * (1.0 - 1e-9) : cos2Bound_;
    offK_ = (o.offcenters && angleOn_) ? o.offcenterFactor / (2.0 * dmath::tan(th / 2)) : INFINITY;
    sizeOn_ = o.maxArea > 0 || o.maxEdge > 0 || bool(o.sizing) || !o.vertexSizing.empty();
    if (!o.vertexSizing.empty()) {
      vh_.assign(o.vertexSizing.begin(), o.vertexSizing.end());
      vh_.resize(T_.vertexCount(), INFINITY);
    }
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (size_t i = 0; i < T_.xy.size(); i += 2) {
      x0 = std::min(x0, T_.xy[i]);
      x1 = std::max(x1, T_.xy[i]);
      y0 = std::min(y0, T_.xy[i + 1]);
      y1 = std::max(y1, T_.xy[i + 1]);
    }
    double diag = dmath::hypot(x1 - x0, y1 - y0);
    reserveForSize();
    minSeg2_ = std::max(diag * 1e-11, o_.minSegmentLength) * std::max(diag * 1e-11, o_.minSegmentLength);
    invDiag2_ = 1.0 / (diag * diag);
  }

  RefineResult run() {
    RefineResult r;
    markAcuteVertices();
    const size_t nt = T_.tris.size();
    for (uint32_t t = 0; t < nt; ++t) {
      if (!s_.inDomain(t)) continue;
      checkTriangle(t);
      checkEncroached(t);
    }
    size_t sinceProgress = 0;
    BadEntry e;
    for (;;) {
      if (insertions_ >= o_.maxInsertions) {
        r.status = Status{Code::IterationLimit, Stage::Refine,
                          "refinement stopped at maxInsertions = " + std::to_string(o_.maxInsertions)};
        break;
      }
      if (++sinceProgress >= 8192) {
        sinceProgress = 0;
        reportProgress();
      }
      if (!enc_.empty()) {
        auto [u, v] = enc_.back();
        enc_.pop_back();
        splitSubsegment(u, v);
        continue;
      }
      if (!bad_.pop(e)) break;
      if (T_.tf[e.t] & (kDead | kOutside | kIsGhost)) continue;
      const Tri& Tt = T_.tris[e.t];
      if (Tt.v[0] != e.a || Tt.v[1] != e.b || Tt.v[2] != e.c) continue;
      splitTriangle(e.t);
    }
    r.insertions = insertions_;
    r.segmentSplits = segmentSplits_;
    r.rejected = rejected_;
    return r;
  }

  //! Exemption rule (see RefineResult::exemptTriangles) for a triangle whose smallest angle is
  //! at corner `s` (opposite the shortest edge).
  bool exempt(uint32_t t, uint32_t s) const {
    const Tri& Tt = T_.tris[t];
    // The small angle is an input angle between two segments.
    if (T_.isConstrained(t, nxt(s)) && T_.isConstrained(t, prv(s))) return true;
    uint32_t p = Tt.v[nxt(s)], q = Tt.v[prv(s)];
    if (!o_.apexOf.empty() && acrossChainWedge(p, q)) return true;
    // Shortest edge joins two segment vertices on segments with a common apex, equidistant.
    if (p < s_.nInput || q < s_.nInput) return false;
    int32_t sp = s_.vseg[p], sq = s_.vseg[q];
    if (sp < 0 || sq < 0 || sp == sq) return false;
    uint32_t apex = kNone;
    uint32_t pa = s_.segA[size_t(sp)], pb = s_.segB[size_t(sp)];
    uint32_t qa = s_.segA[size_t(sq)], qb = s_.segB[size_t(sq)];
    if (pa == qa || pa == qb) apex = pa;
    else if (pb == qa || pb == qb) apex = pb;
    if (apex == kNone) return false;
    const double* x = T_.pt(apex);
    double d1 = dist2(T_.pt(p), x), d2 = dist2(T_.pt(q), x);
    return d1 < 1.002 * d2 && d2 < 1.002 * d1;
  }

  // RefineOptions::apexOf: the apex and chain of vertex v (an input point's own, or for a Steiner
  // vertex those of the segment it lies on); false when it has none.
  bool chainTag(uint32_t v, uint32_t& apex, uint32_t& chain) const {
    if (v < s_.nInput) {
      apex = o_.apexOf[v], chain = o_.chainOf[v];
      return apex != kNoApex;
    }
    const int32_t sg = s_.vseg[v];
    if (sg < 0) return false;
    return segmentTag(s_.segA[size_t(sg)], s_.segB[size_t(sg)], apex, chain);
  }

  // The apex and chain of the input segment ab (RefineOptions::apexOf), if it has them.
  bool segmentTag(uint32_t a, uint32_t b, uint32_t& apex, uint32_t& chain) const {
    if (o_.apexOf[a] == b || (o_.apexOf[a] != kNoApex && o_.apexOf[a] == o_.apexOf[b] && o_.chainOf[a] == o_.chainOf[b])) {
      apex = o_.apexOf[a], chain = o_.chainOf[a];
      return true;
    }
    if (o_.apexOf[b] == a) {
      apex = a, chain = o_.chainOf[b];
      return true;
    }
    return false;
  }

  // Vertex v lies on another chain of the apex of subsegment ab's chain (RefineOptions::apexOf):
  // ab is not split for it. The triangles between the two chains are across the wedge, which no
  // refinement improves (Shewchuk 2002, small input angles); splitting ab for the other side
  // would only make them smaller and more, down the wedge to the apex.
  bool onOtherChain(uint32_t v, uint32_t a, uint32_t b) const {
    if (o_.apexOf.empty()) return false;
    uint32_t av, cv, as, cs;
    if (!chainTag(v, av, cv)) return false;
    const bool tagged = a >= s_.nInput ? chainTag(a, as, cs) : b >= s_.nInput ? chainTag(b, as, cs) : segmentTag(a, b, as, cs);
    return tagged && av == as && cv != cs;
  }

  // Edge pq spans the wedge of an apex (RefineOptions::apexOf).
  bool acrossChainWedge(uint32_t p, uint32_t q) const {
    uint32_t ap, cp, aq, cq;
    if (!chainTag(p, ap, cp) || !chainTag(q, aq, cq) || ap != aq || cp == cq) return false;
    const double* x = T_.pt(ap);
    const double* P = T_.pt(p);
    const double* Q = T_.pt(q);
    const double ux = P[0] - x[0], uy = P[1] - x[1], vx = Q[0] - x[0], vy = Q[1] - x[1];
    const double lp2 = ux * ux + uy * uy, lq2 = vx * vx + vy * vy;
    if (!(lp2 <= 4 * lq2 && lq2 <= 4 * lp2)) return false;
    // seen under less than θ: cos(seen)² > cos²θ with a positive cosine
    const double dot = ux * vx + uy * vy;
    return dot > 0 && dot * dot > cos2Bound_ * lp2 * lq2;
  }

 private:
  CdtState& s_;
  Triangulation& T_;
  const RefineOptions& o_;
  bool angleOn_, sizeOn_, segBoundOn_;
  double cos2Bound_, cos2SegBound_, sin2Bound_, offK_, minSeg2_;
  std::vector<uint8_t> onSegment_;  // per input point: an end of a segment
  std::vector<double> vh_;
  BadQueue bad_;
  std::vector<std::pair<uint32_t, uint32_t>> enc_;
  size_t insertions_ = 0, segmentSplits_ = 0, rejected_ = 0;
  // Subsegments whose split was given up (too short, or no valid cavity): a triangle whose
  // insertion point would need one of them split is given up too, so nothing loops.
  std::unordered_set<uint64_t> unsplittable_;
  double progress_ = 0;

  std::vector<uint8_t> acute_;
  double lensCos2_ = 0;
  double invDiag2_ = 1;

  // Does p encroach upon subsegment ab? Inside the diametral circle (angle apb > 90°), or with
  // diametral lenses (Chew; Shewchuk 2002) inside the lens: angle apb > 180° − 2θ.
  bool encroaches(const double* p, const double* a, const double* b) const {
    double ax = a[0] - p[0], ay = a[1] - p[1], bx = b[0] - p[0], by = b[1] - p[1];
    double dot = ax * bx + ay * by;
    if (dot >= 0) return false;
    return dot * dot >= lensCos2_ * (ax * ax + ay * ay) * (bx * bx + by * by);
  }

  // v lies on a segment: an input point that ends one, or a segment split
  bool onSegment(uint32_t v) const { return v < s_.nInput ? onSegment_[v] != 0 : s_.vseg[v] >= 0; }

  // Input vertices where two segments meet at less than 90 degrees: segments ending there are
  // split on concentric shells around them; and the input vertices on segments.
  void markAcuteVertices() {
    std::vector<std::vector<uint32_t>> nb(s_.nInput);
    for (const auto& kv : s_.subseg) {
      uint32_t a = uint32_t(kv.first >> 32), b = uint32_t(kv.first & 0xFFFFFFFFu);
      nb[a].push_back(b);
      nb[b].push_back(a);
    }
    acute_.assign(s_.nInput, 0);
    onSegment_.assign(s_.nInput, 0);
    for (uint32_t v = 0; v < s_.nInput; ++v) {
      onSegment_[v] = !nb[v].empty();
      const double* p = T_.pt(v);
      for (size_t i = 0; i < nb[v].size() && !acute_[v]; ++i) {
        for (size_t j = i + 1; j < nb[v].size(); ++j) {
          const double* a = T_.pt(nb[v][i]);
          const double* b = T_.pt(nb[v][j]);
          if ((a[0] - p[0]) * (b[0] - p[0]) + (a[1] - p[1]) * (b[1] - p[1]) > 0) {
            acute_[v] = 1;
            break;
          }
        }
      }
    }
  }

  // Reserve the arrays for the expected output when a uniform size bound is given, so the
  // hot loop neither reallocates nor copies (estimates calibrated on data/pslg: Delaunay
  // refinement meshes average ~0.62 maxArea and ~0.205 maxEdge^2 per triangle).
  void reserveForSize() {
    double area = 0;
    for (uint32_t t = 0; t < T_.tris.size(); ++t) {
      if (!s_.inDomain(t)) continue;
      const Tri& Tt = T_.tris[t];
      const double* a = T_.pt(Tt.v[0]);
      const double* b = T_.pt(Tt.v[1]);
      const double* c = T_.pt(Tt.v[2]);
      area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    }
    double est = 0;
    if (o_.maxArea > 0) est = area / (0.60 * o_.maxArea);
    if (o_.maxEdge > 0) est = std::max(est, area / (0.20 * o_.maxEdge * o_.maxEdge));
    if (!(est > 0) || est > 1e9) return;
    size_t nt = T_.tris.size() + size_t(1.04 * est), nv = T_.vertexCount() + size_t(0.52 * est);
    T_.tris.reserve(nt);
    T_.tf.reserve(nt);
    T_.xy.reserve(2 * nv);
    T_.vtri.reserve(nv);
    s_.vseg.reserve(nv);
    s_.vparam.reserve(nv);
  }

  // floor(4 log2 x), approximately (exponent and the top two mantissa bits), for x > 0.
  static int quarterOctave(double x) {
    uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    int e = int((bits >> 52) & 0x7FF) - 1023;
    int m = int((bits >> 50) & 3);
    return 4 * e + m;
  }

  static double dist2(const double* a, const double* b) {
    double dx = a[0] - b[0], dy = a[1] - b[1];
    return dx * dx + dy * dy;
  }

  void reportProgress() {
    if (!o_.progress) return;
    double f = double(insertions_) / double(insertions_ + bad_.size() + 1);
    progress_ = std::max(progress_, std::min(f, 0.99));
    if (!o_.progress(Stage::Refine, progress_)) fail(Code::Cancelled, Stage::Refine, "refinement cancelled");
  }

  double sizeAt(const Tri& Tt, double cx, double cy) const {
    double h = o_.maxEdge > 0 ? o_.maxEdge : INFINITY;
    if (o_.sizing) {
      double v = o_.sizing(cx, cy);
      if (std::isfinite(v) && v > 0) h = std::min(h, v);
    }
    if (!vh_.empty()) {
      double v = (vh_[Tt.v[0]] + vh_[Tt.v[1]] + vh_[Tt.v[2]]) / 3.0;
      if (std::isfinite(v) && v > 0) h = std::min(h, v);
    }
    return h;
  }

  // Quality test; enqueues the triangle if it is skinny (and not exempt) or too big.
  void checkTriangle(uint32_t t) {
    const Tri& Tt = T_.tris[t];
    const double* a = T_.pt(Tt.v[0]);
    const double* b = T_.pt(Tt.v[1]);
    const double* c = T_.pt(Tt.v[2]);
    double ex[3] = {c[0] - b[0], a[0] - c[0], b[0] - a[0]};
    double ey[3] = {c[1] - b[1], a[1] - c[1], b[1] - a[1]};
    double l[3] = {ex[0] * ex[0] + ey[0] * ey[0], ex[1] * ex[1] + ey[1] * ey[1], ex[2] * ex[2] + ey[2] * ey[2]};
    uint32_t s = l[0] < l[1] ? (l[0] < l[2] ? 0 : 2) : (l[1] < l[2] ? 1 : 2);
    // Angle at corner s between edges nxt(s) and prv(s).
    uint32_t i = nxt(s), j = prv(s);
    double dot = ex[i] * ex[j] + ey[i] * ey[j];  // = -(u·w) for the corner vectors
    double cos2 = dot * dot / (l[i] * l[j]);
    int bucket = -1;
    // a triangle with its three vertices on segments is judged by the higher bound when given
    const bool onSegments = segBoundOn_ && onSegment(Tt.v[0]) && onSegment(Tt.v[1]) && onSegment(Tt.v[2]);
    if (angleOn_ && dot < 0 && cos2 > (onSegments ? cos2SegBound_ : cos2Bound_) && !exempt(t, s)) {
      // Shortest edge first, in quarter-octave buckets of the squared length (relative to the
      // bounding box): refining the finest features first gives markedly fewer Steiner points
      // than worst-angle-first (measured on data/pslg; see bench/refine2d_bench.cpp).
      int k = -quarterOctave(l[s] * invDiag2_);
      bucket = BadQueue::kBuckets - 2 - std::max(0, std::min(BadQueue::kBuckets - 2, k));
    } else if (sizeOn_) {
      double cross = ex[2] * (-ey[1]) - ey[2] * (-ex[1]);
      bool big = o_.maxArea > 0 && 0.5 * std::fabs(cross) > o_.maxArea;
      if (!big && (o_.maxEdge > 0 || o_.sizing || !vh_.empty())) {
        double h = sizeAt(Tt, (a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3);
        double lmax = std::max(l[0], std::max(l[1], l[2]));
        big = lmax > h * h;
      }
      if (big) bucket = BadQueue::kBuckets - 1;
    }
    if (bucket >= 0) bad_.push(bucket, BadEntry{t, Tt.v[0], Tt.v[1], Tt.v[2]});
  }

  // Enqueue the constrained edges of domain triangle t that its apex encroaches upon.
  void checkEncroached(uint32_t t) {
    uint8_t con = T_.tf[t] & 7u;
    if (!con) return;
    const Tri& Tt = T_.tris[t];
    for (uint32_t i = 0; i < 3; ++i) {
      if (!((con >> i) & 1u)) continue;
      const double* p = T_.pt(Tt.v[i]);
      const double* a = T_.pt(Tt.v[nxt(i)]);
      const double* b = T_.pt(Tt.v[prv(i)]);
      if (encroaches(p, a, b) && !onOtherChain(Tt.v[i], Tt.v[nxt(i)], Tt.v[prv(i)]))
        enc_.emplace_back(Tt.v[nxt(i)], Tt.v[prv(i)]);
    }
  }

  double paramOf(uint32_t v, int32_t seg) const {
    if (v >= s_.nInput) return s_.vparam[v];
    if (v == s_.segA[size_t(seg)]) return 0.0;
    if (v == s_.segB[size_t(seg)]) return 1.0;
    const double* a = T_.pt(s_.segA[size_t(seg)]);
    const double* b = T_.pt(s_.segB[size_t(seg)]);
    const double* p = T_.pt(v);
    double dx = b[0] - a[0], dy = b[1] - a[1];
    return ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy);
  }

  uint32_t newVertex(double x, double y, int32_t seg, double param, double h) {
    uint32_t v = T_.addVertex(x, y);
    s_.vseg.push_back(seg);
    s_.vparam.push_back(param);
    if (!vh_.empty()) vh_.push_back(h);
    ++insertions_;
    return v;
  }

  void afterInsert(bool split) {
    for (uint32_t f : T_.fan) {
      if (!s_.inDomain(f)) continue;
      checkTriangle(f);
      if (split) checkEncroached(f);
    }
  }

  void splitSubsegment(uint32_t u, uint32_t v) {
    uint32_t h = T_.findEdge(u, v);
    if (h == kNone || !T_.isConstrained(hTri(h), hEdge(h))) return;  // already split
    const double* pu = T_.pt(u);
    const double* pv = T_.pt(v);
    double L2 = dist2(pu, pv);
    if (L2 < minSeg2_ || !o_.splitSegments) {
      ++rejected_;
      unsplittable_.insert(CdtState::key(u, v));
      return;
    }
    int32_t seg = s_.segmentOf(u, v);
    if (seg < 0) fail(Code::InternalError, Stage::Refine, "constrained edge without a segment");
    double tu = paramOf(u, seg), tv = paramOf(v, seg);
    bool acuteU = u < s_.nInput && acute_[u];
    bool acuteV = v < s_.nInput && acute_[v];
    double frac = 0.5;
    if (acuteU != acuteV) {
      // Concentric shells (Ruppert 1995; Shewchuk 2002): split at a power-of-two distance
      // from the shared input vertex, within [1/3, 2/3] of the subsegment.
      double L = std::sqrt(L2);
      double d = 1.0;
      while (d < L / 3) d *= 2;
      while (d > 2 * L / 3) d *= 0.5;
      frac = acuteU ? d / L : 1.0 - d / L;
    }
    double tm = tu + (tv - tu) * frac;
    const double* A = T_.pt(s_.segA[size_t(seg)]);
    const double* B = T_.pt(s_.segB[size_t(seg)]);
    double p[2] = {A[0] + tm * (B[0] - A[0]), A[1] + tm * (B[1] - A[1])};
    if ((p[0] == pu[0] && p[1] == pu[1]) || (p[0] == pv[0] && p[1] == pv[1])) {
      ++rejected_;
      unsplittable_.insert(CdtState::key(u, v));
      return;
    }
    if (!T_.findCavity(p, hTri(h), h)) {
      T_.clearCavity();
      ++rejected_;
      unsplittable_.insert(CdtState::key(u, v));
      return;
    }
    double hv = 0;
    if (!vh_.empty()) hv = vh_[u] + (vh_[v] - vh_[u]) * frac;
    uint32_t nv = newVertex(p[0], p[1], seg, tm, hv);
    T_.commitCavity(nv, u, v);
    ++segmentSplits_;
    afterInsert(true);
  }

  enum class Walk { Inside, Blocked, OnVertex };

  // Straight walk from the centroid of t toward p; stops at constrained edges.
  Walk walk(const double* p, uint32_t& t, uint32_t& edge) const {
    const Tri& T0 = T_.tris[t];
    const double* a0 = T_.pt(T0.v[0]);
    const double* b0 = T_.pt(T0.v[1]);
    const double* c0 = T_.pt(T0.v[2]);
    const double q[2] = {(a0[0] + b0[0] + c0[0]) / 3, (a0[1] + b0[1] + c0[1]) / 3};
    for (size_t guard = 0; guard < T_.tris.size() + 8; ++guard) {
      const Tri& Tt = T_.tris[t];
      const double* v[3] = {T_.pt(Tt.v[0]), T_.pt(Tt.v[1]), T_.pt(Tt.v[2])};
      double o[3];
      int neg[2], nneg = 0;
      for (uint32_t i = 0; i < 3; ++i) {
        o[i] = orient2d(v[nxt(i)], v[prv(i)], p);
        if (o[i] < 0) neg[nneg++] = int(i);
      }
      if (nneg == 0) {
        for (uint32_t i = 0; i < 3; ++i) {
          if (v[i][0] == p[0] && v[i][1] == p[1]) return Walk::OnVertex;
        }
        for (uint32_t i = 0; i < 3; ++i) {
          if (o[i] == 0 && T_.isConstrained(t, i)) {
            edge = mkH(t, i);
            return Walk::Blocked;
          }
        }
        return Walk::Inside;
      }
      uint32_t i = uint32_t(neg[0]);
      if (nneg == 2) {
        // Exit through the edge (x, y) with x right of the ray q -> p and y left of it.
        const double* x = v[nxt(i)];
        const double* y = v[prv(i)];
        if (!(orient2d(q, p, x) <= 0 && orient2d(q, p, y) >= 0)) i = uint32_t(neg[1]);
      }
      if (T_.isConstrained(t, i)) {
        edge = mkH(t, i);
        return Walk::Blocked;
      }
      t = hTri(Tt.n[i]);
    }
    fail(Code::InternalError, Stage::Refine, "refinement walk did not terminate");
  }

  void splitTriangle(uint32_t t) {
    const Tri& Tt = T_.tris[t];
    const double* a = T_.pt(Tt.v[0]);
    const double* b = T_.pt(Tt.v[1]);
    const double* c = T_.pt(Tt.v[2]);
    // Circumcenter relative to a.
    double bx = b[0] - a[0], by = b[1] - a[1], cx = c[0] - a[0], cy = c[1] - a[1];
    double lb = bx * bx + by * by, lc = cx * cx + cy * cy;
    double d = 2.0 * (bx * cy - by * cx);
    double ux = (cy * lb - by * lc) / d, uy = (bx * lc - cx * lb) / d;
    double p[2] = {a[0] + ux, a[1] + uy};
    if (std::isfinite(offK_)) {
      // Off-center (Üngör 2009): on the bisector of the shortest edge, no farther from it
      // than the point that sees that edge under the angle bound.
      double l0 = dist2(b, c), l1 = lc, l2 = lb;
      const double *P, *Q;
      double L2;
      if (l0 <= l1 && l0 <= l2) {
        P = b, Q = c, L2 = l0;
      } else if (l1 <= l2) {
        P = c, Q = a, L2 = l1;
      } else {
        P = a, Q = b, L2 = l2;
      }
      double mx = (P[0] + Q[0]) / 2, my = (P[1] + Q[1]) / 2;
      double wx = p[0] - mx, wy = p[1] - my;
      double dc = std::sqrt(wx * wx + wy * wy);
      double hoff = offK_ * std::sqrt(L2);
      if (dc > hoff) {
        p[0] = mx + wx * (hoff / dc);
        p[1] = my + wy * (hoff / dc);
      }
    }
    if (!std::isfinite(p[0]) || !std::isfinite(p[1])) {
      ++rejected_;
      return;
    }
    uint32_t loc = t, edge = kNone;
    Walk w = walk(p, loc, edge);
    if (w == Walk::OnVertex) {
      ++rejected_;
      return;
    }
    BadEntry again{t, Tt.v[0], Tt.v[1], Tt.v[2]};
    if (w == Walk::Blocked) {
      const Tri& B = T_.tris[hTri(edge)];
      uint32_t bu = B.v[nxt(hEdge(edge))], bv = B.v[prv(hEdge(edge))];
      if (unsplittable_.count(CdtState::key(bu, bv))) {
        ++rejected_;
        return;
      }
      enc_.emplace_back(bu, bv);
      checkTriangle(again.t);
      return;
    }
    if (!T_.findCavity(p, loc, kNone)) {
      T_.clearCavity();
      ++rejected_;
      return;
    }
    bool encroached = false, stuck = false;
    for (const CavityEdge& ce : T_.boundary) {
      if (!(ce.flags & 1u)) continue;
      const double* pu = T_.pt(ce.u);
      const double* pv = T_.pt(ce.v);
      if (encroaches(p, pu, pv)) {
        enc_.emplace_back(ce.u, ce.v);
        encroached = true;
        if (!unsplittable_.empty() && unsplittable_.count(CdtState::key(ce.u, ce.v))) stuck = true;
      }
    }
    if (stuck) {
      enc_.clear();
      T_.clearCavity();
      ++rejected_;
      return;
    }
    if (encroached) {
      T_.clearCavity();
      checkTriangle(again.t);
      return;
    }
    double hv = 0;
    if (!vh_.empty()) {
      const Tri& L = T_.tris[loc];
      const double* x = T_.pt(L.v[0]);
      const double* y = T_.pt(L.v[1]);
      const double* z = T_.pt(L.v[2]);
      double area = (y[0] - x[0]) * (z[1] - x[1]) - (y[1] - x[1]) * (z[0] - x[0]);
      double w0 = ((y[0] - p[0]) * (z[1] - p[1]) - (y[1] - p[1]) * (z[0] - p[0])) / area;
      double w1 = ((z[0] - p[0]) * (x[1] - p[1]) - (z[1] - p[1]) * (x[0] - p[0])) / area;
      hv = w0 * vh_[L.v[0]] + w1 * vh_[L.v[1]] + (1 - w0 - w1) * vh_[L.v[2]];
    }
    uint32_t nv = newVertex(p[0], p[1], -1, 0.0, hv);
    T_.commitCavity(nv);
    afterInsert(false);
  }
};

}  // namespace

RefineResult refinePslg(const Pslg& pslg, const RefineOptions& options) {
  auto t0 = std::chrono::steady_clock::now();
  if (!(options.minAngleDeg >= 0 && options.minAngleDeg <= 34.0))
    fail(Code::InvalidArgument, Stage::Refine, "minAngleDeg must be in [0, 34]");
  if (!(options.maxArea >= 0) || !(options.maxEdge >= 0) || !std::isfinite(options.maxArea) ||
      !std::isfinite(options.maxEdge))
    fail(Code::InvalidArgument, Stage::Refine, "maxArea and maxEdge must be finite and >= 0");
  if (!(options.segmentTriangleMinAngleDeg >= 0 && options.segmentTriangleMinAngleDeg <= 40.0))
    fail(Code::InvalidArgument, Stage::Refine, "segmentTriangleMinAngleDeg must be in [0, 40]");
  if (!(options.offcenterFactor > 0 && options.offcenterFactor <= 0.99))
    fail(Code::InvalidArgument, Stage::Refine, "offcenterFactor must be in (0, 0.99]");
  if (!(options.minSegmentLength >= 0) || !std::isfinite(options.minSegmentLength))
    fail(Code::InvalidArgument, Stage::Refine, "minSegmentLength must be finite and >= 0");
  if (!options.vertexSizing.empty() && options.vertexSizing.size() != pslg.points.size() / 2)
    fail(Code::InvalidArgument, Stage::Refine, "vertexSizing needs one value per input point");
  if (!options.apexOf.empty()) {
    const size_t n = pslg.points.size() / 2;
    bool ok = options.apexOf.size() == n && options.chainOf.size() == n;
    for (size_t i = 0; ok && i < n; ++i) ok = options.apexOf[i] == kNoApex || (options.apexOf[i] < n && options.apexOf[i] != i);
    if (!ok) fail(Code::InvalidArgument, Stage::Refine, "apexOf and chainOf need one entry per input point, each apex an other input point or none");
  }
  CdtState s;
  buildCdt(pslg, options.cdt, options.progress, s);
  Refiner ref(s, options);
  RefineResult r = ref.run();
  // Quality summary over the domain triangles.
  const Triangulation& T = s.tri;
  double minSin2 = INFINITY;
  const double th = options.minAngleDeg * kPi / 180.0;
  const double sin2Bound = dmath::sin(th) * dmath::sin(th);
  for (uint32_t t = 0; t < T.tris.size(); ++t) {
    if (!s.inDomain(t)) continue;
    const Tri& Tt = T.tris[t];
    const double* p[3] = {T.pt(Tt.v[0]), T.pt(Tt.v[1]), T.pt(Tt.v[2])};
    double l[3];
    for (uint32_t i = 0; i < 3; ++i) {
      double dx = p[prv(i)][0] - p[nxt(i)][0], dy = p[prv(i)][1] - p[nxt(i)][1];
      l[i] = dx * dx + dy * dy;
    }
    uint32_t k = l[0] < l[1] ? (l[0] < l[2] ? 0 : 2) : (l[1] < l[2] ? 1 : 2);
    double area2 = std::fabs((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]));
    // sin(angle at k) = area2 / (|e_nxt| |e_prv|)
    double sin2 = area2 * area2 / (l[nxt(k)] * l[prv(k)]);
    if (options.minAngleDeg > 0 && sin2 < sin2Bound && ref.exempt(t, k)) {
      ++r.exemptTriangles;
      continue;
    }
    minSin2 = std::min(minSin2, sin2);
  }
  extractMesh(s, r.mesh, true);
  r.minAngleDeg = std::isfinite(minSin2) ? dmath::asin(std::sqrt(std::min(1.0, minSin2))) * 180.0 / kPi : 0.0;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (options.progress && !options.progress(Stage::Refine, 1.0))
    fail(Code::Cancelled, Stage::Refine, "refinement cancelled");
  return r;
}

}  // namespace conformesh::planar
