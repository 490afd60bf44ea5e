#include "conformal/overlay.h"

#include "core/bucket_sort.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "conformal/triangle_geometry.h"
#include "core/detmath.h"
#include "core/vec3.h"

namespace conformesh::conformal {

namespace {

using IT = IntrinsicTriangulation;

[[noreturn]] void numerical(const std::string& msg) { fail(Code::NumericalFailure, Stage::Flatten, msg); }

// Change of basis across the edge of halfedge hx (face F -> face G of twin(hx)). With
// F = (a, b, c), hx = a->b, G = (b, a, d), the vertex d in F's coordinates is
// d = x a + y b + z c (z < 0: d lies beyond the edge).
//  Hyperbolic: decorated light-like vectors with -<v_p, v_q> = e^{lam_pq} and <v_d, v_d> = 0.
//  Euclidean: affine (barycentric) coordinates of d in the unfolded quad, x + y + z = 1.
struct Unfold {
  int sa, sb, sc;  // slots of a, b, c in F
  int ta, tb, td;  // slots of a, b, d in G
  double x, y, z;
};

Unfold unfold(const IT& T, int hx, OverlayGeometry geo) {
  const int tw = T.twin[hx];
  Unfold U;
  U.sa = hx % 3;
  U.sb = IT::next(hx) % 3;
  U.sc = IT::prev(hx) % 3;
  U.tb = tw % 3;
  U.ta = IT::next(tw) % 3;
  U.td = IT::prev(tw) % 3;
  const double lab = T.lambda[T.edge[hx]], lbc = T.lambda[T.edge[IT::next(hx)]], lac = T.lambda[T.edge[IT::prev(hx)]];
  const double lad = T.lambda[T.edge[IT::next(tw)]], lbd = T.lambda[T.edge[IT::prev(tw)]];
  if (geo == OverlayGeometry::Hyperbolic) {
    U.z = -dmath::exp(0.5 * (lad + lbd - lac - lbc));
    U.x = dmath::exp(lbd - lab) + dmath::exp(0.5 * (lad + lbd + lbc - lac) - lab);
    U.y = dmath::exp(lad - lab) + dmath::exp(0.5 * (lad + lbd + lac - lbc) - lab);
  } else {
    double lf[3] = {lab, lbc, lac}, lg[3] = {lab, lad, lbd}, af[3], ag[3];
    anglesFromLogLengths(lf, af);  // af[1]: angle at a (opposite b-c)
    anglesFromLogLengths(lg, ag);  // ag[2]: angle at a (opposite d-b)
    const double Lab = dmath::exp(0.5 * lab), Lac = dmath::exp(0.5 * lac), Lad = dmath::exp(0.5 * lad);
    const double cx = Lac * dmath::cos(af[1]), cy = Lac * dmath::sin(af[1]);
    const double dx = Lad * dmath::cos(ag[2]), dy = -Lad * dmath::sin(ag[2]);
    U.z = dy / cy;
    U.y = (dx - U.z * cx) / Lab;
    U.x = 1.0 - U.y - U.z;
  }
  return U;
}

// Line coefficients (n . P = 0) from F coordinates to G coordinates. noinline: with emcc 3.1.6
// (clang 14) at -O2 the inlined stores by run-time slot index into std::array were
// miscompiled in the tracing loop (traces went astray in WASM only; -O0 and native were
// correct); kept out of line, the WASM and native results agree.
__attribute__((noinline)) Vec3 mapLine(const Unfold& U, const Vec3& n) {
  Vec3 m;
  m[U.ta] = n[U.sa];
  m[U.tb] = n[U.sb];
  m[U.td] = U.x * n[U.sa] + U.y * n[U.sb] + U.z * n[U.sc];
  const double s = std::max(std::fabs(m[0]), std::max(std::fabs(m[1]), std::fabs(m[2])));
  if (s > 0)
    for (int k = 0; k < 3; ++k) m[k] /= s;
  return m;
}

// Point (decorated vector) coordinates from F to G.
__attribute__((noinline)) Vec3 mapPoint(const Unfold& U, const Vec3& p) {
  Vec3 q;
  const double dd = p[U.sc] / U.z;
  q[U.td] = dd;
  q[U.ta] = p[U.sa] - U.x * dd;
  q[U.tb] = p[U.sb] - U.y * dd;
  return q;
}


bool invert3(const double m[9], double out[9]) {  // row-major
  const double c00 = m[4] * m[8] - m[5] * m[7], c01 = m[5] * m[6] - m[3] * m[8], c02 = m[3] * m[7] - m[4] * m[6];
  const double det = m[0] * c00 + m[1] * c01 + m[2] * c02;
  if (!(std::fabs(det) > 0) || !std::isfinite(det)) return false;
  const double id = 1.0 / det;
  out[0] = c00 * id;
  out[1] = (m[2] * m[7] - m[1] * m[8]) * id;
  out[2] = (m[1] * m[5] - m[2] * m[4]) * id;
  out[3] = c01 * id;
  out[4] = (m[0] * m[8] - m[2] * m[6]) * id;
  out[5] = (m[2] * m[3] - m[0] * m[5]) * id;
  out[6] = c02 * id;
  out[7] = (m[1] * m[6] - m[0] * m[7]) * id;
  out[8] = (m[0] * m[4] - m[1] * m[3]) * id;
  return true;
}

struct Segment {
  int face;     // target face
  int hin;      // source halfedge i->j
  Vec3 vi, vj;  // endpoints of the source edge in the face's basis
};

// Source face (a, b, c) with h = a->b, given a and b in target face t's coordinates: the
// matrix whose columns (in the source face's slot order) are the coordinates of its vertices.
void sourceFaceMatrix(const IT& src, const IT& dst, int t, int h, const Vec3& va, const Vec3& vb, OverlayGeometry geo,
                      double M[9]) {
  const double Lab = dmath::exp(src.lambda[src.edge[h]]);
  const double Lac = dmath::exp(src.lambda[src.edge[IT::prev(h)]]), Lbc = dmath::exp(src.lambda[src.edge[IT::next(h)]]);
  Vec3 vc;
  if (geo == OverlayGeometry::Hyperbolic) {
    const double L01 = dmath::exp(dst.lambda[dst.edge[3 * t]]), L12 = dmath::exp(dst.lambda[dst.edge[3 * t + 1]]),
                 L20 = dmath::exp(dst.lambda[dst.edge[3 * t + 2]]);
    const double G[9] = {0, -L01, -L20, -L01, 0, -L12, -L20, -L12, 0};
    double Gi[9];
    invert3(G, Gi);
    const Vec3 c = cross(va, vb);
    const Vec3 W = {Gi[0] * c[0] + Gi[1] * c[1] + Gi[2] * c[2], Gi[3] * c[0] + Gi[4] * c[1] + Gi[5] * c[2],
                    Gi[6] * c[0] + Gi[7] * c[1] + Gi[8] * c[2]};
    // W is Minkowski-orthogonal to va, vb; det[va, vb, W] = (va x vb) . W = <W, W> > 0, so +W
    // points to the left of a->b, where c lies.
    const double WW = dot(c, W);
    if (!(WW > 0)) numerical("flatten/overlay: degenerate edge in the hyperbolic chart");
    const double alpha = Lbc / Lab, beta = Lac / Lab, gamma = std::sqrt(2 * Lac * Lbc / (Lab * WW));
    for (int q = 0; q < 3; ++q) vc[q] = alpha * va[q] + beta * vb[q] + gamma * W[q];
  } else {
    // Target face in a local frame: q0 = 0, q1 on the x axis, q2 above.
    double lt[3] = {dst.lambda[dst.edge[3 * t]], dst.lambda[dst.edge[3 * t + 1]], dst.lambda[dst.edge[3 * t + 2]]}, at[3];
    anglesFromLogLengths(lt, at);
    const double q[3][2] = {{0, 0},
                            {dmath::exp(0.5 * lt[0]), 0},
                            {dmath::exp(0.5 * lt[2]) * dmath::cos(at[1]), dmath::exp(0.5 * lt[2]) * dmath::sin(at[1])}};
    double pa[2] = {0, 0}, pb[2] = {0, 0};
    for (int s = 0; s < 3; ++s)
      for (int k = 0; k < 2; ++k) {
        pa[k] += va[s] * q[s][k];
        pb[k] += vb[s] * q[s][k];
      }
    double ls[3] = {src.lambda[src.edge[h]], src.lambda[src.edge[IT::next(h)]], src.lambda[src.edge[IT::prev(h)]]}, as[3];
    anglesFromLogLengths(ls, as);  // as[1]: angle at a (opposite b-c)
    const double ex = pb[0] - pa[0], ey = pb[1] - pa[1], el = dmath::hypot(ex, ey);
    const double cx = std::sqrt(Lac) * dmath::cos(as[1]), cy = std::sqrt(Lac) * dmath::sin(as[1]);
    const double pc[2] = {pa[0] + (cx * ex - cy * ey) / el, pa[1] + (cx * ey + cy * ex) / el};
    // Barycentric coordinates of pc in the target face.
    const double b2 = pc[1] / q[2][1];
    const double b1 = (pc[0] - b2 * q[2][0]) / q[1][0];
    vc = {1 - b1 - b2, b1, b2};
  }
  const int sa = h % 3, sb = IT::next(h) % 3, sc = IT::prev(h) % 3;
  for (int q = 0; q < 3; ++q) {
    M[3 * q + sa] = va[q];
    M[3 * q + sb] = vb[q];
    M[3 * q + sc] = vc[q];
  }
}

}  // namespace

OverlayMap buildOverlayMap(const IT& src, const IT& T, OverlayGeometry geo) {
  OverlayMap O;
  const int nF = T.nF;
  // Fans of the target triangulation sorted by position.
  std::vector<int> fanStart(T.nV + 1, 0), fan(3 * size_t(nF));
  for (int h = 0; h < 3 * nF; ++h) ++fanStart[T.vert[h] + 1];
  for (int v = 0; v < T.nV; ++v) fanStart[v + 1] += fanStart[v];
  {
    std::vector<int> fill(fanStart.begin(), fanStart.end() - 1);
    for (int h = 0; h < 3 * nF; ++h) fan[fill[T.vert[h]]++] = h;
    for (int v = 0; v < T.nV; ++v)
      std::sort(fan.begin() + fanStart[v], fan.begin() + fanStart[v + 1],
                [&](int a, int b) { return T.horoPos[a] != T.horoPos[b] ? T.horoPos[a] < T.horoPos[b] : a < b; });
  }
  // Target edges that are source edges (never flipped, or flipped back onto the same curve).
  std::vector<int> sourceOfTarget(T.nE, -1);
  for (int e = 0; e < T.nE; ++e)
    if (T.origin[e] >= 0) sourceOfTarget[e] = T.origin[e];

  std::vector<std::vector<Segment>> segs(nF);
  std::vector<Segment> path;
  std::vector<int> pathCross;
  const size_t maxCrossings = 40 * size_t(T.nE) + 1000000;
  size_t crossings = 0;

  for (int ein = 0; ein < src.nE; ++ein) {
    if (T.origin[ein] == ein) continue;  // survived
    const int hin = src.edgeHalf[ein];
    const int i = src.vert[hin], j = src.tip(hin);
    const double p = src.horoPos[hin];
    const int s0 = fanStart[i], s1 = fanStart[i + 1];
    int k = int(std::upper_bound(fan.begin() + s0, fan.begin() + s1, p,
                                 [&](double val, int h) { return val < T.horoPos[h]; }) -
                fan.begin()) - 1;
    double off;
    if (k < s0) {
      if (T.boundaryVertex[i]) numerical("flatten/overlay: edge direction outside the fan");
      k = s1 - 1;
      off = p + T.horoTotal[i] - T.horoPos[fan[k]];
    } else {
      off = p - T.horoPos[fan[k]];
    }
    const int g = fan[k];
    const double corner = T.cornerSize(g);
    const double f = std::clamp(off / corner, 0.0, 1.0);
    const int y = T.tip(g), z = T.vert[IT::prev(g)];
    // An edge that was flipped away and back is the same curve again: its direction matches a
    // target edge to round-off (flips carry positions with relative error ~1e-15 each).
    if (f < 1e-7 && y == j) {
      sourceOfTarget[T.edge[g]] = ein;
      continue;
    }
    if (f > 1 - 1e-7 && z == j) {
      sourceOfTarget[T.edge[IT::prev(g)]] = ein;
      continue;
    }
    // The curve from i hits edge y-z at e_y + r e_z.
    double r;
    if (geo == OverlayGeometry::Hyperbolic) {
      r = f / (1 - f) * dmath::exp(T.lambda[T.edge[g]] - T.lambda[T.edge[IT::prev(g)]]);
    } else {
      double lam[3] = {T.lambda[T.edge[3 * (g / 3)]], T.lambda[T.edge[3 * (g / 3) + 1]], T.lambda[T.edge[3 * (g / 3) + 2]]}, ang[3];
      anglesFromLogLengths(lam, ang);
      const double thetaY = ang[IT::prev(g) % 3];  // at y, opposite z->i
      const double phi = f * corner;
      const double t = dmath::exp(0.5 * (T.lambda[T.edge[g]] - T.lambda[T.edge[IT::next(g)]])) * dmath::sin(phi) / dmath::sin(phi + thetaY);
      r = t / (1 - t);
      if (!(r >= 0) || !std::isfinite(r)) r = f / (1 - f);
    }
    int face = g / 3;
    Vec3 n{0, 0, 0}, vi{0, 0, 0};
    n[IT::next(g) % 3] = -r / (1 + r);
    n[IT::prev(g) % 3] = 1 / (1 + r);
    vi[g % 3] = 1;
    int exitH = IT::next(g);
    path.clear();
    pathCross.clear();
    path.push_back({face, hin, vi, {0, 0, 0}});
    for (;;) {
      if (T.twin[exitH] < 0) numerical("flatten/overlay: an edge left the domain while being traced");
      if (++crossings > maxCrossings) fail(Code::TooLarge, Stage::Flatten, "flatten/overlay: too many crossings");
      if (path.size() > size_t(T.nF) + 2)
        numerical("flatten/overlay: edge " + std::to_string(i) + "-" + std::to_string(j) + " lost while traced (f " +
                  std::to_string(f) + ", corner " + std::to_string(corner) + ", y " + std::to_string(y) + ", z " + std::to_string(z) +
                  ", p " + std::to_string(p) + ", k " + std::to_string(k - s0) + "/" + std::to_string(s1 - s0) + ")");
      const Unfold U = unfold(T, exitH, geo);
      n = mapLine(U, n);
      vi = mapPoint(U, vi);
      pathCross.push_back(exitH);
      const int tw = T.twin[exitH];
      face = tw / 3;
      path.push_back({face, hin, vi, {0, 0, 0}});
      const int d = T.vert[IT::prev(tw)];
      const double na = n[U.ta], nb = n[U.tb], nd = n[U.td];
      if (d == j && std::fabs(nd) <= 1e-9 * std::max(std::fabs(na), std::fabs(nb))) break;
      if ((na > 0) != (nd > 0) && na != 0 && nd != 0)
        exitH = IT::next(tw);  // a->d
      else if ((nb > 0) != (nd > 0) && nb != 0 && nd != 0)
        exitH = IT::prev(tw);  // d->b
      else if (d == j)
        break;
      else
        numerical("flatten/overlay: a traced edge passes through a vertex");
    }
    Vec3 vj{0, 0, 0};
    vj[IT::prev(T.twin[pathCross.back()]) % 3] = 1;
    path.back().vj = vj;
    for (int s = int(pathCross.size()) - 1; s >= 0; --s) {
      vj = mapPoint(unfold(T, T.twin[pathCross[s]], geo), vj);
      path[s].vj = vj;
    }
    for (const Segment& sg : path) segs[sg.face].push_back(sg);
  }
  O.crossings = crossings;

  O.candStart.assign(nF + 1, 0);
  std::vector<int> cand;
  std::vector<double> inv;
  auto addCandidate = [&](int tin, const double M[9]) {
    for (int c : cand)
      if (c == tin) return;
    double Mi[9];
    if (!invert3(M, Mi)) numerical("flatten/overlay: singular overlay cell");
    cand.push_back(tin);
    inv.insert(inv.end(), Mi, Mi + 9);
  };
  for (int t = 0; t < nF; ++t) {
    cand.clear();
    inv.clear();
    for (const Segment& sg : segs[t]) {
      double M[9];
      sourceFaceMatrix(src, T, t, sg.hin, sg.vi, sg.vj, geo, M);
      addCandidate(sg.hin / 3, M);
      const int tw = src.twin[sg.hin];
      if (tw >= 0) {
        sourceFaceMatrix(src, T, t, tw, sg.vj, sg.vi, geo, M);
        addCandidate(tw / 3, M);
      }
    }
    if (segs[t].empty()) {
      int found = -1;
      for (int s = 0; s < 3 && found < 0; ++s) {
        const int ein = sourceOfTarget[T.edge[3 * t + s]];
        if (ein < 0) continue;
        for (int h : {src.edgeHalf[ein], src.twin[src.edgeHalf[ein]]})
          if (h >= 0 && src.vert[h] == T.vert[3 * t + s] && src.tip(h) == T.tip(3 * t + s)) found = h;
      }
      if (found < 0) numerical("flatten/overlay: a face matches no source face");
      double M[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
      const int tin = found / 3;
      for (int q = 0; q < 3; ++q)
        for (int s2 = 0; s2 < 3; ++s2)
          if (T.vert[3 * t + s2] == src.vert[3 * tin + q]) M[3 * s2 + q] = 1;
      addCandidate(tin, M);
    }
    O.candStart[t + 1] = O.candStart[t] + int(cand.size());
    O.candFace.insert(O.candFace.end(), cand.begin(), cand.end());
    O.candInv.insert(O.candInv.end(), inv.begin(), inv.end());
  }
  return O;
}

bool OverlayMap::map(int t, const double X[3], int& face, double bary[3], double& margin) const {
  int best = -1;
  double bestScore = -1e300, bestC[3] = {0, 0, 0};
  for (int c = candStart[t]; c < candStart[t + 1]; ++c) {
    const double* Mi = &candInv[9 * size_t(c)];
    double C[3], sa = 0;
    for (int q = 0; q < 3; ++q) {
      C[q] = Mi[3 * q] * X[0] + Mi[3 * q + 1] * X[1] + Mi[3 * q + 2] * X[2];
      sa += std::fabs(C[q]);
    }
    if (!(sa > 0)) continue;
    const double score = std::min(C[0], std::min(C[1], C[2])) / sa;
    if (score > bestScore) {
      bestScore = score;
      best = c;
      for (int q = 0; q < 3; ++q) bestC[q] = C[q];
    }
  }
  if (best < 0) return false;
  double sc = 0;
  for (double& c : bestC) {
    c = std::max(c, 0.0);
    sc += c;
  }
  if (!(sc > 0)) return false;
  face = candFace[best];
  margin = bestScore;
  for (int q = 0; q < 3; ++q) bary[q] = bestC[q] / sc;
  return true;
}

Pullback::Pullback(std::vector<double> inputPositions, std::vector<int> inputTriangles, std::vector<double> xy,
                   std::vector<int> finalTriangles, std::vector<double> u, OverlayMap finalToDelaunay,
                   OverlayMap delaunayToInput)
    : inPos_(std::move(inputPositions)),
      inTri_(std::move(inputTriangles)),
      xy_(std::move(xy)),
      fTri_(std::move(finalTriangles)),
      finalToDelaunay_(std::move(finalToDelaunay)),
      delaunayToInput_(std::move(delaunayToInput)) {
  const int nF = int(fTri_.size() / 3), nV = int(xy_.size() / 2);
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  for (int v = 0; v < nV; ++v)
    for (int k = 0; k < 2; ++k) {
      lo[k] = std::min(lo[k], xy_[2 * v + k]);
      hi[k] = std::max(hi[k], xy_[2 * v + k]);
    }
  const double w = std::max(hi[0] - lo[0], hi[1] - lo[1]);
  diam_ = w > 0 ? w : 1.0;
  const int n = std::max(1, int(std::sqrt(double(nF) / 2)));
  cell_ = diam_ / n * (1 + 1e-9);
  lo_[0] = lo[0];
  lo_[1] = lo[1];
  nx_ = std::max(1, int((hi[0] - lo[0]) / cell_) + 1);
  ny_ = std::max(1, int((hi[1] - lo[1]) / cell_) + 1);
  std::vector<std::array<int, 4>> range(nF);
  gridStart_.assign(size_t(nx_) * ny_ + 1, 0);
  auto cx = [&](double x) { return std::clamp(int((x - lo_[0]) / cell_), 0, nx_ - 1); };
  auto cy = [&](double y) { return std::clamp(int((y - lo_[1]) / cell_), 0, ny_ - 1); };
  for (int t = 0; t < nF; ++t) {
    double bx0 = 1e300, bx1 = -1e300, by0 = 1e300, by1 = -1e300;
    for (int s = 0; s < 3; ++s) {
      const int v = fTri_[3 * t + s];
      bx0 = std::min(bx0, xy_[2 * v]);
      bx1 = std::max(bx1, xy_[2 * v]);
      by0 = std::min(by0, xy_[2 * v + 1]);
      by1 = std::max(by1, xy_[2 * v + 1]);
    }
    range[t] = {cx(bx0), cx(bx1), cy(by0), cy(by1)};
    for (int X = range[t][0]; X <= range[t][1]; ++X)
      for (int Y = range[t][2]; Y <= range[t][3]; ++Y) ++gridStart_[size_t(Y) * nx_ + X + 1];
  }
  for (size_t c = 0; c + 1 < gridStart_.size(); ++c) gridStart_[c + 1] += gridStart_[c];
  gridFaces_.resize(gridStart_.back());
  std::vector<int> fill(gridStart_.begin(), gridStart_.end() - 1);
  for (int t = 0; t < nF; ++t)
    for (int X = range[t][0]; X <= range[t][1]; ++X)
      for (int Y = range[t][2]; Y <= range[t][3]; ++Y) gridFaces_[fill[size_t(Y) * nx_ + X]++] = t;
  // Per corner, the factor from Euclidean barycentrics to base-decorated coordinates.
  fScale_.resize(3 * size_t(nF));
  for (int t = 0; t < nF; ++t) {
    double umax = -1e300;
    for (int k = 0; k < 3; ++k) umax = std::max(umax, u[fTri_[3 * t + k]]);
    for (int k = 0; k < 3; ++k) fScale_[3 * size_t(t) + k] = dmath::exp(u[fTri_[3 * t + k]] - umax);
  }
  // Face adjacency for the walk: corners sorted by their opposite edge; an edge with exactly two
  // corners joins two faces.
  fNbr_.assign(3 * size_t(nF), -1);
  std::vector<std::pair<uint64_t, int>> edges(3 * size_t(nF));
  for (int t = 0; t < nF; ++t)
    for (int k = 0; k < 3; ++k) {
      const uint64_t a = uint32_t(fTri_[3 * t + (k + 1) % 3]), b = uint32_t(fTri_[3 * t + (k + 2) % 3]);
      edges[3 * size_t(t) + k] = {std::min(a, b) << 32 | std::max(a, b), 3 * t + k};
    }
  uint64_t maxLo = 0;
  for (const auto& e : edges) maxLo = std::max(maxLo, e.first >> 32);
  bucketSort(edges, size_t(maxLo) + 1, [](const std::pair<uint64_t, int>& e) { return size_t(e.first >> 32); },
             [](const std::pair<uint64_t, int>& x, const std::pair<uint64_t, int>& y) { return x < y; });
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j].first == edges[i].first) ++j;
    if (j - i == 2) {
      fNbr_[edges[i].second] = edges[i + 1].second / 3;
      fNbr_[edges[i + 1].second] = edges[i].second / 3;
    }
    i = j;
  }
}

void Pullback::faceProducts(int t, double x, double y, double w[3], double& area) const {
  const double* a = &xy_[2 * fTri_[3 * t]];
  const double* b = &xy_[2 * fTri_[3 * t + 1]];
  const double* d = &xy_[2 * fTri_[3 * t + 2]];
  area = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]);
  w[0] = (b[0] - x) * (d[1] - y) - (b[1] - y) * (d[0] - x);
  w[1] = (d[0] - x) * (a[1] - y) - (d[1] - y) * (a[0] - x);
  w[2] = (a[0] - x) * (b[1] - y) - (a[1] - y) * (b[0] - x);
}

double Pullback::coordsFrom(const double w[3], double area, double B[3]) const {
  B[0] = w[0] / area;
  B[1] = w[1] / area;
  B[2] = 1 - B[0] - B[1];
  // Signed distance-like measure relative to the domain size.
  return std::min(B[0], std::min(B[1], B[2])) * std::sqrt(area) / diam_;
}

bool Pullback::faceCoords(int t, double x, double y, double B[3], double& score) const {
  double w[3], area;
  faceProducts(t, x, y, w, area);
  if (!(area > 0)) return false;
  score = coordsFrom(w, area, B);
  return true;
}

int Pullback::gridSearch(double x, double y, double B[3], double tolerance) const {
  if (fTri_.empty()) return -1;
  const int X = int(std::floor((x - lo_[0]) / cell_)), Y = int(std::floor((y - lo_[1]) / cell_));
  int bestFace = -1;
  double bestMin = -1e300;
  for (int ring = 0; ring <= 1 && bestMin < 0; ++ring)
    for (int gx = std::max(0, X - ring); gx <= std::min(nx_ - 1, X + ring); ++gx)
      for (int gy = std::max(0, Y - ring); gy <= std::min(ny_ - 1, Y + ring); ++gy) {
        const size_t c = size_t(gy) * nx_ + gx;
        for (int k = gridStart_[c]; k < gridStart_[c + 1]; ++k) {
          const int t = gridFaces_[k];
          double Bt[3], m;
          if (!faceCoords(t, x, y, Bt, m)) continue;
          if (m > bestMin) {
            bestMin = m;
            bestFace = t;
            for (int q = 0; q < 3; ++q) B[q] = Bt[q];
          }
        }
      }
  return bestFace < 0 || bestMin < -tolerance ? -1 : bestFace;
}

int Pullback::walk(double x, double y, int hintFace, double B[3], int& steps) const {
  // A point this far inside a face (in the grid search's score) is in no other face of an
  // embedded layout, by far more than the round-off of the score (~1e-16): the grid search
  // would pick the same face with the same coordinates.
  constexpr double kSurelyInside = 1e-12;
  constexpr int kMaxSteps = 1000;
  const int nF = int(fTri_.size() / 3);
  if (hintFace < 0 || hintFace >= nF) return -1;
  int t = hintFace;
  for (int step = 0; step < kMaxSteps; ++step) {
    // Most steps only ask which edge the point is beyond: the signs of the barycentric
    // coordinates times the face's doubled area (no division or square root); where the point
    // is inside, the coordinates and score are faceCoords' (the grid search's).
    double w[3], area;
    faceProducts(t, x, y, w, area);
    if (!(area > 0)) return -1;
    int k;
    if (w[0] > 0 && w[1] > 0 && w[2] > 0) {
      const double m = coordsFrom(w, area, B);
      if (m >= kSurelyInside) {
        steps = step;
        return t;
      }
      k = B[0] <= B[1] && B[0] <= B[2] ? 0 : (B[1] <= B[2] ? 1 : 2);
      if (!(B[k] < 0)) return -1;  // inside, but too near an edge to be sure
    } else {
      // cross the edge opposite the most negative coordinate (the point is beyond its line)
      k = w[0] <= w[1] && w[0] <= w[2] ? 0 : (w[1] <= w[2] ? 1 : 2);
      if (!(w[k] < 0)) return -1;  // on an edge (or NaN): the grid search decides
    }
    t = fNbr_[3 * size_t(t) + k];
    if (t < 0) return -1;  // off the domain across this edge, or a hole: the grid search decides
  }
  return -1;
}

bool Pullback::locate(double x, double y, PullbackPoint& out, double tolerance) const {
  double B[3];
  const int t = gridSearch(x, y, B, tolerance);
  return t >= 0 && finish(t, B, out);
}

bool Pullback::locate(double x, double y, int hintFace, PullbackPoint& out, double tolerance) const {
  double B[3];
  int steps = -1;
  const int t = walk(x, y, hintFace, B, steps);
  if (t < 0) return locate(x, y, out, tolerance);
  if (!finish(t, B, out)) return false;
  out.walkSteps = steps;
  return true;
}

bool Pullback::locateLayout(double x, double y, int& face, int vertices[3], double bary[3], double tolerance) const {
  int steps = -1;
  int t = walk(x, y, face, bary, steps);
  if (t < 0) t = gridSearch(x, y, bary, tolerance);
  if (t < 0) return false;
  double s = 0;
  for (int k = 0; k < 3; ++k) s += bary[k] = std::max(bary[k], 0.0);
  for (int k = 0; k < 3; ++k) {
    bary[k] /= s;
    vertices[k] = fTri_[3 * size_t(t) + k];
  }
  face = t;
  return true;
}

bool Pullback::finish(int t, const double B[3], PullbackPoint& out) const {
  double bestB[3] = {B[0], B[1], B[2]};
  double s = 0;
  for (double& b : bestB) {
    b = std::max(b, 0.0);
    s += b;
  }
  // Final Euclidean barycentrics -> base-decorated (hyperbolic) coordinates.
  double Xc[3];
  for (int k = 0; k < 3; ++k) Xc[k] = bestB[k] / s * fScale_[3 * size_t(t) + k];
  int dFace, inFace;
  double dBary[3], m1, m2;
  if (!finalToDelaunay_.map(t, Xc, dFace, dBary, m1)) return false;
  if (!delaunayToInput_.map(dFace, dBary, inFace, out.bary, m2)) return false;
  out.face = uint32_t(inFace);
  out.margin = std::min(m1, m2);
  out.layoutFace = t;
  out.walkSteps = -1;
  for (int k = 0; k < 3; ++k) {
    out.position[k] = 0;
    for (int q = 0; q < 3; ++q) out.position[k] += out.bary[q] * inPos_[3 * size_t(inTri_[3 * out.face + q]) + k];
  }
  return true;
}

}  // namespace conformesh::conformal
