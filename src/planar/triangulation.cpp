// Planar triangulation core: ghost-closed triangle structure, walking point location,
// Bowyer–Watson insertion. See triangulation.h.
#include "planar/triangulation.h"

#include <cmath>

#include "core/status.h"
#include "core/triangle_corner.h"

namespace conformesh::planar {

void Triangulation::setConstrained(uint32_t t, uint32_t e, bool on) {
  if (on)
    tf[t] = uint8_t(tf[t] | (1u << e));
  else
    tf[t] = uint8_t(tf[t] & ~(1u << e));
}

void Triangulation::setEdgeConstrained(uint32_t h, bool on) {
  setConstrained(hTri(h), hEdge(h), on);
  uint32_t o = tris[hTri(h)].n[hEdge(h)];
  setConstrained(hTri(o), hEdge(o), on);
}

uint32_t Triangulation::addVertex(double x, double y) {
  xy.push_back(x);
  xy.push_back(y);
  vtri.push_back(kNone);
  return uint32_t(vtri.size() - 1);
}

uint32_t Triangulation::newTri() {
  if (!freeTris.empty()) {
    uint32_t t = freeTris.back();
    freeTris.pop_back();
    tf[t] = 0;
    return t;
  }
  if (tris.size() >= (size_t(1) << 30))
    fail(Code::TooLarge, Stage::Refine, "planar triangulation: more than 2^30 triangles");
  tris.push_back(Tri{});
  tf.push_back(0);
  return uint32_t(tris.size() - 1);
}

void Triangulation::freeTri(uint32_t t) {
  tf[t] = kDead;
  freeTris.push_back(t);
}

bool Triangulation::inConflict(uint32_t t, const double* p) const {
  const Tri& T = tris[t];
  if (tf[t] & kIsGhost) {
    uint32_t k = T.v[0] == kGhost ? 0 : (T.v[1] == kGhost ? 1 : 2);
    const double* a = pt(T.v[nxt(k)]);
    const double* b = pt(T.v[prv(k)]);
    double o = orient2d(a, b, p);
    if (o > 0) return true;
    if (o < 0) return false;
    // On the hull line: in conflict iff strictly between a and b.
    double d = (p[0] - a[0]) * (b[0] - a[0]) + (p[1] - a[1]) * (b[1] - a[1]);
    double l = (b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]);
    return d > 0 && d < l;
  }
  return incircle(pt(T.v[0]), pt(T.v[1]), pt(T.v[2]), p) > 0;
}

uint32_t Triangulation::locate(const double* p, uint32_t t) const {
  uint32_t rng = 0x9E3779B9u ^ uint32_t(tris.size());
  const size_t cap = 4 * tris.size() + 64;
  for (size_t step = 0; step < cap; ++step) {
    const Tri& T = tris[t];
    if (tf[t] & kIsGhost) {
      if (inConflict(t, p)) return t;
      uint32_t k = T.v[0] == kGhost ? 0 : (T.v[1] == kGhost ? 1 : 2);
      t = hTri(T.n[k]);
      continue;
    }
    rng ^= rng << 13;
    rng ^= rng >> 17;
    rng ^= rng << 5;
    uint32_t r = rng % 3;
    bool moved = false;
    for (uint32_t k = 0; k < 3; ++k) {
      uint32_t i = (r + k) % 3;
      if (orient2d(pt(T.v[nxt(i)]), pt(T.v[prv(i)]), p) < 0) {
        t = hTri(T.n[i]);
        moved = true;
        break;
      }
    }
    if (!moved) return t;
  }
  fail(Code::InternalError, Stage::Refine, "planar triangulation: point location did not terminate");
}

bool Triangulation::findCavity(const double* p, uint32_t t0, uint32_t splitEdge) {
  cavity.clear();
  boundary.clear();
  stack_.clear();
  tf[t0] |= kMark;
  cavity.push_back(t0);
  stack_.push_back(t0);
  if (splitEdge != kNone) {
    uint32_t t1 = hTri(tris[t0].n[hEdge(splitEdge)]);
    tf[t1] |= kMark;
    cavity.push_back(t1);
    stack_.push_back(t1);
  }
  bool starShaped = true;
  while (!stack_.empty()) {
    uint32_t t = stack_.back();
    stack_.pop_back();
    for (uint32_t i = 0; i < 3; ++i) {
      const Tri& T = tris[t];
      uint32_t h = T.n[i];
      uint32_t nt = hTri(h);
      if (tf[nt] & kMark) continue;
      uint32_t u = T.v[nxt(i)], v = T.v[prv(i)];
      bool con = (tf[t] >> i) & 1u;
      if (tf[t] & kOutside) {
        // Outside the domain only the topology matters: no expansion, no geometric check.
        boundary.push_back(CavityEdge{u, v, h, uint8_t((con ? 1u : 0u) | kOutside)});
        continue;
      }
      double o = 1.0;
      if (u != kGhost && v != kGhost) o = orient2d(pt(u), pt(v), p);
      if (!con && o >= 0 && inConflict(nt, p)) {
        tf[nt] |= kMark;
        cavity.push_back(nt);
        stack_.push_back(nt);
      } else {
        // A fan triangle (u, v, p) must be counter-clockwise: p strictly left of u -> v.
        if (o <= 0) starShaped = false;
        boundary.push_back(CavityEdge{u, v, h, uint8_t((con ? 1u : 0u) | (tf[t] & kOutside))});
      }
    }
  }
  return starShaped;
}

void Triangulation::clearCavity() {
  for (uint32_t t : cavity) tf[t] &= uint8_t(~kMark);
}

void Triangulation::commitCavity(uint32_t p, uint32_t splitA, uint32_t splitB) {
  const size_t B = boundary.size(), C = cavity.size();
  if (fanStart_.size() < vtri.size()) fanStart_.resize(vtri.size() + vtri.size() / 2 + 16);
  fan.clear();
  for (size_t i = 0; i < B; ++i) fan.push_back(i < C ? cavity[i] : newTri());
  for (size_t i = B; i < C; ++i) freeTri(cavity[i]);
  for (size_t i = 0; i < B; ++i) {
    const CavityEdge& e = boundary[i];
    uint32_t t = fan[i];
    Tri& T = tris[t];
    T.v[0] = e.u;
    T.v[1] = e.v;
    T.v[2] = p;
    uint8_t f = uint8_t(e.flags & kOutside);
    if (e.flags & 1u) f |= uint8_t(kCon0 << 2);
    if (e.u == kGhost || e.v == kGhost) f |= kIsGhost;
    tf[t] = f;
    link(mkH(t, 2), e.outer);
    if (e.u == kGhost) {
      ghostStart_ = uint32_t(i);
    } else {
      fanStart_[e.u] = uint32_t(i);
      vtri[e.u] = t;
    }
  }
  for (size_t i = 0; i < B; ++i) {
    uint32_t v = boundary[i].v;
    uint32_t j = v == kGhost ? ghostStart_ : fanStart_[v];
    link(mkH(fan[i], 0), mkH(fan[j], 1));
  }
  vtri[p] = fan[0];
  for (size_t i = 0; i < B && !fan.empty(); ++i) {
    if (!(tf[fan[i]] & kIsGhost)) {
      vtri[p] = fan[i];
      break;
    }
  }
  if (splitA != kNone) {
    for (size_t i = 0; i < B; ++i) {
      const CavityEdge& e = boundary[i];
      if (e.u == splitA || e.u == splitB) setConstrained(fan[i], 1, true);
      if (e.v == splitA || e.v == splitB) setConstrained(fan[i], 0, true);
    }
  }
}

uint32_t Triangulation::findEdge(uint32_t u, uint32_t v) const {
  uint32_t t = vtri[u];
  if (t == kNone) return kNone;
  const uint32_t start = t;
  for (size_t guard = 0; guard < tris.size() + 4; ++guard) {
    const Tri& T = tris[t];
    const uint32_t i = uint32_t(cornerOf(T.v, u));
    if (T.v[nxt(i)] == v) return mkH(t, prv(i));
    t = hTri(T.n[nxt(i)]);
    if (t == start) return kNone;
  }
  fail(Code::InternalError, Stage::Refine, "planar triangulation: vertex ring is not closed");
}

void Triangulation::buildDelaunay(const std::vector<uint32_t>& order) {
  if (order.size() < 3) fail(Code::InvalidPslg, Stage::Refine, "fewer than 3 distinct points");
  uint32_t a = order[0], b = order[1], c = kNone;
  size_t ci = 0;
  for (size_t i = 2; i < order.size(); ++i) {
    if (orient2d(pt(a), pt(b), pt(order[i])) != 0) {
      c = order[i];
      ci = i;
      break;
    }
  }
  if (c == kNone) fail(Code::InvalidPslg, Stage::Refine, "all points are collinear");
  if (orient2d(pt(a), pt(b), pt(c)) < 0) std::swap(a, b);
  tris.reserve(2 * order.size() + 16);
  tf.reserve(2 * order.size() + 16);
  uint32_t r = newTri(), g1 = newTri(), g2 = newTri(), g3 = newTri();
  tris[r] = Tri{{a, b, c}, {0, 0, 0}};
  tris[g1] = Tri{{b, a, kGhost}, {0, 0, 0}};  // outside edge a-b
  tris[g2] = Tri{{c, b, kGhost}, {0, 0, 0}};  // outside edge b-c
  tris[g3] = Tri{{a, c, kGhost}, {0, 0, 0}};  // outside edge c-a
  tf[g1] = tf[g2] = tf[g3] = kIsGhost;
  link(mkH(r, 2), mkH(g1, 2));
  link(mkH(r, 0), mkH(g2, 2));
  link(mkH(r, 1), mkH(g3, 2));
  // ghost (x, y, G): edge 0 = (y, G) pairs with edge 1 = (G, y) of the ghost starting at y.
  link(mkH(g1, 0), mkH(g3, 1));
  link(mkH(g3, 0), mkH(g2, 1));
  link(mkH(g2, 0), mkH(g1, 1));
  vtri[a] = vtri[b] = vtri[c] = r;
  uint32_t last = r;
  for (size_t i = 2; i < order.size(); ++i) {
    if (i == ci) continue;
    uint32_t p = order[i];
    uint32_t t = locate(pt(p), last);
    findCavity(pt(p), t, kNone);
    commitCavity(p);
    last = vtri[p];
  }
}

}  // namespace conformesh::planar
