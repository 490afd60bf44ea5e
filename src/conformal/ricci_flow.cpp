#include "conformal/ricci_flow.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "conformal/layout.h"
#include "conformal/triangle_geometry.h"
#include "core/detmath.h"

namespace conformesh::conformal {

namespace {

using IT = IntrinsicTriangulation;
using Clock = std::chrono::steady_clock;

// Adds the wall time of its scope to a counter (phase profile of the flow).
struct ScopedTimer {
  double& acc;
  Clock::time_point t0 = Clock::now();
  explicit ScopedTimer(double& a) : acc(a) {}
  ~ScopedTimer() { acc += std::chrono::duration<double>(Clock::now() - t0).count(); }
};

void faceAngles(const IT& T, int f, const std::vector<double>& u, double ang[3], bool* valid = nullptr) {
  double lam[3];
  for (int k = 0; k < 3; ++k) lam[k] = T.scaledLambda(3 * f + k, u);
  const bool ok = anglesFromLogLengths(lam, ang);
  if (valid) *valid = ok;
}

// Angle opposite halfedge h in its face.
double oppositeAngle(const IT& T, int h, const std::vector<double>& u) {
  double ang[3];
  faceAngles(T, h / 3, u, ang);
  return ang[h % 3];
}

bool edgeIsDelaunay(const IT& T, int e, const std::vector<double>& u, double tol) {
  const int h = T.edgeHalf[e], t = T.twin[h];
  if (t < 0) return true;
  return oppositeAngle(T, h, u) + oppositeAngle(T, t, u) <= kPi + tol;
}

// Polygon inscribed in a circle with chords c: radius R with sum 2 asin(c/2R) = 2 pi.
// Returns false when no such circle exists (one chord longer than the rest can span).
bool circumRadius(const std::vector<double>& c, double& R) {
  double cmax = 0.0, P = 0.0;
  for (double x : c) {
    cmax = std::max(cmax, x);
    P += x;
  }
  auto F = [&](double r) {
    double s = 0.0;
    for (double x : c) s += 2.0 * dmath::asin(std::min(1.0, x / (2.0 * r)));
    return s - 2.0 * kPi;
  };
  double lo = 0.5 * cmax, hi = std::max(P, lo);
  if (F(lo) < 0.0) return false;
  R = std::max(lo, P / (2.0 * kPi));
  for (int it = 0; it < 200; ++it) {
    const double f = F(R);
    if (f > 0.0)
      lo = R;
    else
      hi = R;
    if (hi - lo <= 1e-15 * hi) break;
    double df = 0.0;
    for (double x : c) {
      const double q = x / (2.0 * R);
      if (q < 1.0) df -= 2.0 * q / (R * std::sqrt((1.0 - q) * (1.0 + q)));
    }
    double Rn = (df < 0.0) ? R - f / df : 0.5 * (lo + hi);
    if (!(Rn > lo && Rn < hi)) Rn = 0.5 * (lo + hi);
    if (std::fabs(Rn - R) <= 1e-16 * R) {
      R = Rn;
      break;
    }
    R = Rn;
  }
  return true;
}

// Delaunay flips with the corner angles kept per face: every face's angles are computed once,
// and again only for the two faces of each flip (the test of an edge reads two cached angles).
// On return angle/valid describe the final triangulation for the metric u.
long long flipToDelaunayWithAngles(IT& T, const std::vector<double>& u, long long maxFlips, bool euclidean,
                                   std::vector<double>& angle, std::vector<char>& valid) {
  constexpr double tol = 1e-12;
  angle.resize(size_t(3) * T.nF);
  valid.resize(T.nF);
  for (int f = 0; f < T.nF; ++f) {
    bool ok;
    faceAngles(T, f, u, &angle[3 * size_t(f)], &ok);
    valid[f] = ok;
  }
  std::vector<int> stack;
  stack.reserve(T.nE);
  std::vector<char> queued(T.nE, 0);
  for (int e = 0; e < T.nE; ++e)
    if (T.twin[T.edgeHalf[e]] >= 0) {
      stack.push_back(e);
      queued[e] = 1;
    }
  long long done = 0;
  while (!stack.empty()) {
    const int e = stack.back();
    stack.pop_back();
    queued[e] = 0;
    if (!T.canFlip(e)) continue;
    const int h0 = T.edgeHalf[e], t0 = T.twin[h0];
    if (angle[h0] + angle[t0] <= kPi + tol) continue;
    if (done >= maxFlips)
      fail(Code::IterationLimit, Stage::Flatten, "flatten: Delaunay flips exceeded their cap (" + std::to_string(maxFlips) + ")");
    if (euclidean)
      T.flipEuclidean(e);
    else
      T.flip(e);
    ++done;
    const int h = T.edgeHalf[e], t = T.twin[h];
    for (int f : {h / 3, t / 3}) {
      bool ok;
      faceAngles(T, f, u, &angle[3 * size_t(f)], &ok);
      valid[f] = ok;
    }
    const int sides[4] = {IT::next(h), IT::prev(h), IT::next(t), IT::prev(t)};
    for (int sd : sides) {
      const int se = T.edge[sd];
      if (T.twin[sd] >= 0 && !queued[se]) {
        queued[se] = 1;
        stack.push_back(se);
      }
    }
  }
  return done;
}

class Flow {
 public:
  Flow(IT& T, const FlowOptions& o, const ProgressFn& p) : T_(T), opt_(o), progress_(p) {}
  FlowResult run();

 private:
  void setupBoundary();
  void setGauge(int pins);
  bool circle_ = false;
  int pins_ = 1;
  void updateTargets();
  // Flip, angles, curvature, targets and the gradient for the current u. Returns false when a
  // triangle violates the triangle inequality.
  bool evaluate();
  void gatherGradient();  // grad_ from K_ and Kbar_ for the current unknowns
  long long maxFlips() const { return 200LL * T_.nE + 10000; }

  IT& T_;
  const FlowOptions& opt_;
  const ProgressFn& progress_;
  std::vector<double> u_, angle_, K_, Kbar_, grad_;
  std::vector<char> valid_;  // per face: triangle inequality holds
  std::vector<int> free_;  // per vertex: unknown index or -1 (fixed)
  int nFree_ = 0;
  int outer_ = 0;
  std::vector<char> loopNeumann_;  // per loop: targets from the circle / corner rule
  // Derivative of the circle targets of one loop (see applyTargetJacobian).
  struct LoopJacobian {
    int loop = -1;
    double sgn = 1, W = 0;
    std::vector<double> w;  // per loop edge: q / sqrt(1 - q^2), q = c / 2R
  };
  std::vector<LoopJacobian> jac_;
  void applyTargetJacobian(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  // Newton's linear systems. The Hessian is the cotangent Laplacian L(u), applied matrix-free
  // from per-halfedge weights; it is preconditioned by a sparse Cholesky factor of L at an
  // earlier u. L changes little along the flow (a conformal scaling moves the angles only by
  // O(h |grad u|) per triangle, and only a few flips happen), so a factor is reused for every
  // Newton step and refreshed only when the preconditioned Krylov solver needs more than
  // kFreshFactorIterations: inexact Newton (Dembo–Eisenstat–Steihaug 1982) with forcing term
  // eta = min(1e-2, error), which keeps the local convergence quadratic.
  static constexpr int kFreshFactorIterations = 25;
  void computeWeights();
  void applyL(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  void applyPreconditioner(const Eigen::VectorXd& r, Eigen::VectorXd& z);
  void factor();
  bool factorCovers() const;
  bool pcg(const Eigen::VectorXd& b, Eigen::VectorXd& x, double tol, int maxIt);
  bool gmres(const Eigen::VectorXd& b, Eigen::VectorXd& x, double tol, int maxIt);
  bool solveNewton(const Eigen::VectorXd& b, Eigen::VectorXd& x, bool moving, double tol);
  std::vector<double> cornerKbar_;  // per vertex: NaN unless a corner
  std::vector<double> w_;           // per halfedge: 1/2 cot of the opposite angle (Newton point)
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver_;
  bool factored_ = false;
  std::vector<int> factorIndex_;    // per vertex: unknown of the factored matrix, or -1
  // The factor P L D L' P' as plain arrays for the preconditioner's solves: L's values in single
  // precision (|L_ij| <= 1 for this diagonally dominant M-matrix, and a preconditioner needs no
  // more digits; the Krylov solver works in double), which cuts the memory traffic that bounds
  // the triangular solves by a third. slot_: per free unknown, its row in the permuted factor.
  std::vector<int> lStart_, lRow_, slot_;
  std::vector<float> lVal_;
  std::vector<double> dInv_, y_;
  std::vector<Eigen::Triplet<double>> trip_;
  Eigen::SparseMatrix<double> L_;
  FlowResult R_;
};

void Flow::setupBoundary() {
  const int nL = int(T_.loops.size());
  // Outer loop: the longest in the input metric.
  double best = -1.0;
  for (int k = 0; k < nL; ++k) {
    double len = 0.0;
    for (int e : T_.loopEdges[k]) len += dmath::exp(0.5 * T_.lambda[e]);
    if (len > best) {
      best = len;
      outer_ = k;
    }
  }
  loopNeumann_.assign(nL, 1);
  if (opt_.boundary == BoundaryCondition::Free) loopNeumann_[outer_] = 0;
  setGauge(1);
  cornerKbar_.assign(T_.nV, std::nan(""));
  circle_ = opt_.boundary == BoundaryCondition::Circle || (opt_.boundary == BoundaryCondition::Corners && opt_.corners.empty());
  if (opt_.boundary == BoundaryCondition::Corners) {
    std::vector<int> loopOf(T_.nV, -1);
    for (int k = 0; k < nL; ++k)
      for (int v : T_.loops[k]) loopOf[v] = k;
    for (const auto& c : opt_.corners) {
      if (c.first < 0 || c.first >= T_.nV || loopOf[c.first] < 0)
        fail(Code::InvalidArgument, Stage::Flatten, "flatten: corner " + std::to_string(c.first) + " is not a boundary vertex");
      if (loopOf[c.first] != outer_)
        fail(Code::InvalidArgument, Stage::Flatten,
             "flatten: corner " + std::to_string(c.first) + " lies on an inner loop; corners are supported on the outer loop (inner loops become circles)");
      if (!(c.second > 0.0 && c.second < 2.0 * kPi))
        fail(Code::InvalidArgument, Stage::Flatten, "flatten: corner angle must be in (0, 2 pi)");
      cornerKbar_[c.first] = kPi - c.second;
    }
    // Gauss–Bonnet: the targets on the outer loop must turn by 2 pi in all (interior Kbar = 0,
    // inner loops are circles). The smooth outer vertices take the rest, 2 pi - sum (pi -
    // angle), in proportion to their share of the input's boundary length: fixed targets, so
    // the energy stays convex and Newton converges quadratically (spreading by the current flat
    // lengths instead made the targets move with u, and the frozen-target iteration could
    // stall or diverge on jagged boundaries). When no smooth vertex exists (a jagged boundary:
    // detectCorners marks every zigzag vertex), or the rest would give a smooth vertex an angle
    // outside (0, 2 pi), the angles of a curved patch sum to (n - 2) pi + its total Gaussian
    // curvature, which no straight-edged polygon has: every outer angle is then scaled by
    // (n - 2) pi / sum so that they close (ratios kept, every angle stays positive).
    if (opt_.corners.empty()) return;  // the circle
    const auto& outerLoop = T_.loops[outer_];
    const auto& outerEdges = T_.loopEdges[outer_];
    const size_t n = outerLoop.size();
    double sumC = 0.0, wRest = 0.0;
    std::vector<double> share(n, 0.0);
    for (size_t i = 0; i < n; ++i) {
      const int v = outerLoop[i];
      if (!std::isnan(cornerKbar_[v])) {
        sumC += cornerKbar_[v];
      } else {
        share[i] = 0.5 * (dmath::exp(0.5 * T_.lambda[outerEdges[(i + n - 1) % n]]) + dmath::exp(0.5 * T_.lambda[outerEdges[i]]));
        wRest += share[i];
      }
    }
    const double rest = 2.0 * kPi - sumC;
    bool feasible = wRest > 0.0;
    for (size_t i = 0; i < n && feasible; ++i)
      if (std::isnan(cornerKbar_[outerLoop[i]]) && !(std::fabs(rest * share[i] / wRest) < kPi)) feasible = false;
    if (feasible) {
      for (size_t i = 0; i < n; ++i)
        if (std::isnan(cornerKbar_[outerLoop[i]])) cornerKbar_[outerLoop[i]] = rest * share[i] / wRest;
    } else if (n >= 3) {
      double sumAngle = 0.0;
      for (int v : outerLoop) sumAngle += std::isnan(cornerKbar_[v]) ? kPi : kPi - cornerKbar_[v];
      const double scale = (double(n) - 2.0) * kPi / sumAngle;
      for (int v : outerLoop) cornerKbar_[v] = kPi - scale * (std::isnan(cornerKbar_[v]) ? kPi : kPi - cornerKbar_[v]);
      R_.cornerAngleScale = scale;
    }
  }
}

void Flow::setGauge(int pins) {
  free_.assign(T_.nV, 0);
  const auto& outerLoop = T_.loops[outer_];
  if (opt_.boundary == BoundaryCondition::Free) {
    for (int v : outerLoop) free_[v] = -1;
  } else {
    // Circle: the solutions form the 3-dimensional family of Möbius automorphisms of the disk
    // composed with scaling, so for the exact Newton step u is pinned at three outer vertices
    // (the equations there then hold automatically). Otherwise only the scale is pinned.
    const size_t n = outerLoop.size();
    if (pins == 3 && n >= 3)
      for (size_t k = 0; k < 3; ++k) free_[outerLoop[k * n / 3]] = -1;
    else
      free_[outerLoop[0]] = -1;
  }
  pins_ = pins;
  nFree_ = 0;
  for (int v = 0; v < T_.nV; ++v)
    if (free_[v] == 0) free_[v] = nFree_++;
}

void Flow::updateTargets() {
  Kbar_.assign(T_.nV, 0.0);
  jac_.clear();
  std::vector<double> c;
  for (size_t k = 0; k < T_.loops.size(); ++k) {
    if (!loopNeumann_[k]) continue;
    const auto& loop = T_.loops[k];
    const auto& le = T_.loopEdges[k];
    const size_t n = loop.size();
    c.resize(n);
    double m = -1e300;
    for (size_t i = 0; i < n; ++i) m = std::max(m, T_.lambda[le[i]] + u_[loop[i]] + u_[loop[(i + 1) % n]]);
    double P = 0.0;
    for (size_t i = 0; i < n; ++i) {
      c[i] = dmath::exp(0.5 * (T_.lambda[le[i]] + u_[loop[i]] + u_[loop[(i + 1) % n]] - m));
      P += c[i];
    }
    const double sgn = (int(k) == outer_) ? 1.0 : -1.0;
    bool corners = false;
    if (int(k) == outer_ && opt_.boundary == BoundaryCondition::Corners)
      for (int v : loop)
        if (!std::isnan(cornerKbar_[v])) corners = true;
    if (corners) {  // fixed targets, set up once (setupBoundary)
      for (int v : loop) Kbar_[v] = cornerKbar_[v];
      continue;
    }
    double R;
    if (circumRadius(c, R)) {
      for (size_t i = 0; i < n; ++i)
        Kbar_[loop[i]] = sgn * (dmath::asin(std::min(1.0, c[(i + n - 1) % n] / (2 * R))) + dmath::asin(std::min(1.0, c[i] / (2 * R))));
      LoopJacobian J;
      J.loop = int(k);
      J.sgn = sgn;
      J.w.resize(n);
      for (size_t i = 0; i < n; ++i) {
        const double q = std::min(c[i] / (2 * R), 1.0 - 1e-16);
        J.w[i] = q / std::sqrt((1 - q) * (1 + q));
        J.W += J.w[i];
      }
      jac_.push_back(std::move(J));
    } else {  // no circumscribed circle: turning by arc length
      for (size_t i = 0; i < n; ++i) Kbar_[loop[i]] = sgn * kPi * (c[(i + n - 1) % n] + c[i]) / P;
    }
  }
}

bool Flow::evaluate() {
  ++R_.profile.evaluations;
  int bad = 0;
  if (opt_.flips) {
    ScopedTimer tm(R_.profile.flips);
    flipToDelaunayWithAngles(T_, u_, maxFlips(), false, angle_, valid_);
    for (char ok : valid_) bad += !ok;
  } else {
    ScopedTimer tm(R_.profile.angles);
    bad = computeAngles(T_, u_, angle_);
  }
  ScopedTimer tm(R_.profile.angles);
  K_ = vertexCurvature(T_, angle_);
  updateTargets();
  gatherGradient();
  return bad == 0;
}

void Flow::gatherGradient() {
  grad_.assign(nFree_, 0.0);
  for (int v = 0; v < T_.nV; ++v)
    if (free_[v] >= 0) grad_[free_[v]] = K_[v] - Kbar_[v];
}

// d Kbar / du applied to x (free unknowns). For the inscribed polygon, with q_e = c_e / 2R,
// Kbar_i = s (asin q_{i-1} + asin q_i), dc_e / c_e = (du_a + du_b) / 2 and R fixed by
// sum 2 asin q_e = 2 pi: dKbar_i = s sum_{e at i} w_e (dc_e/c_e - dR/R),
// dR/R = sum_e w_e dc_e/c_e / sum_e w_e, w_e = q_e / sqrt(1 - q_e^2).
void Flow::applyTargetJacobian(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  y.setZero(nFree_);
  std::vector<double> dc;
  for (const LoopJacobian& J : jac_) {
    const auto& loop = T_.loops[J.loop];
    const size_t n = loop.size();
    dc.assign(n, 0.0);
    double dR = 0;
    auto xv = [&](int v) { return free_[v] >= 0 ? x[free_[v]] : 0.0; };
    for (size_t i = 0; i < n; ++i) {
      dc[i] = 0.5 * (xv(loop[i]) + xv(loop[(i + 1) % n]));
      dR += J.w[i] * dc[i];
    }
    dR /= J.W;
    for (size_t i = 0; i < n; ++i) {
      const int v = loop[i];
      if (free_[v] < 0) continue;
      const size_t im = (i + n - 1) % n;
      y[free_[v]] += J.sgn * (J.w[im] * (dc[im] - dR) + J.w[i] * (dc[i] - dR));
    }
  }
}

void Flow::computeWeights() {
  w_.resize(size_t(3) * T_.nF);
  for (int h = 0; h < 3 * T_.nF; ++h) w_[h] = 0.5 * cotOfAngle(angle_[h]);
}

// y = L x over the free unknowns (fixed vertices are zero in x): L_ii = sum w, L_ij = -w.
void Flow::applyL(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  y.setZero(nFree_);
  const int nH = 3 * T_.nF;
  for (int h = 0; h < nH; ++h) {
    const int fi = free_[T_.vert[h]], fj = free_[T_.tip(h)];
    const double d = w_[h] * ((fi >= 0 ? x[fi] : 0.0) - (fj >= 0 ? x[fj] : 0.0));
    if (fi >= 0) y[fi] += d;
    if (fj >= 0) y[fj] -= d;
  }
}

// Whether every current unknown is an unknown of the factored matrix. The factor is built over
// the vertices that no gauge fixes (Free: all but the outer loop; otherwise all but the first
// outer vertex), so for the 3-pin Möbius gauge it is the inverse of a slightly larger matrix,
// restricted: a rank-2 difference that the Krylov solver absorbs in a couple of iterations.
bool Flow::factorCovers() const {
  if (!factored_) return false;
  for (int v = 0; v < T_.nV; ++v)
    if (free_[v] >= 0 && factorIndex_[v] < 0) return false;
  return true;
}

void Flow::factor() {
  ScopedTimer ta(R_.profile.assemble);
  factorIndex_.assign(T_.nV, -1);
  int n = 0;
  const auto& outerLoop = T_.loops[outer_];
  std::vector<char> fixed(T_.nV, 0);
  if (opt_.boundary == BoundaryCondition::Free)
    for (int v : outerLoop) fixed[v] = 1;
  else
    fixed[outerLoop[0]] = 1;
  for (int v = 0; v < T_.nV; ++v)
    if (!fixed[v]) factorIndex_[v] = n++;
  trip_.clear();
  trip_.reserve(size_t(T_.nF) * 12);
  for (int h = 0; h < 3 * T_.nF; ++h) {
    const double w = w_[h];
    const int fi = factorIndex_[T_.vert[h]], fj = factorIndex_[T_.tip(h)];
    if (fi >= 0) trip_.emplace_back(fi, fi, w);
    if (fj >= 0) trip_.emplace_back(fj, fj, w);
    if (fi >= 0 && fj >= 0) {
      trip_.emplace_back(fi, fj, -w);
      trip_.emplace_back(fj, fi, -w);
    }
  }
  L_.resize(n, n);
  L_.setFromTriplets(trip_.begin(), trip_.end());
  {
    // The pattern changes with every flip, and one factorization is the common case: no reuse.
    ScopedTimer tz(R_.profile.analyze);
    ++R_.profile.analyses;
    solver_.analyzePattern(L_);
  }
  ScopedTimer tf(R_.profile.factor);
  ++R_.profile.factorizations;
  solver_.factorize(L_);
  if (solver_.info() != Eigen::Success)
    fail(Code::NumericalFailure, Stage::Flatten, "flatten: the cotangent Laplacian could not be factorized");
  factored_ = true;
  const auto& Lf = solver_.matrixL().nestedExpression();  // unit lower triangle, column-major
  lStart_.assign(Lf.outerIndexPtr(), Lf.outerIndexPtr() + n + 1);
  lRow_.assign(Lf.innerIndexPtr(), Lf.innerIndexPtr() + lStart_[n]);
  lVal_.resize(lStart_[n]);
  for (int p = 0; p < lStart_[n]; ++p) {
    const double x = Lf.valuePtr()[p];
    if (!(std::fabs(x) < 1e30)) fail(Code::NumericalFailure, Stage::Flatten, "flatten: the Laplacian factor is not finite");
    lVal_[p] = float(x);
  }
  const auto& D = solver_.vectorD();
  dInv_.resize(n);
  for (int i = 0; i < n; ++i) dInv_[i] = 1.0 / D[i];
  const auto& perm = solver_.permutationP().indices();
  std::vector<int> slotOfFactor(n);
  for (int i = 0; i < n; ++i) slotOfFactor[i] = perm.size() == n ? perm[i] : i;
  slot_.assign(T_.nV, -1);
  for (int v = 0; v < T_.nV; ++v)
    if (factorIndex_[v] >= 0) slot_[v] = slotOfFactor[factorIndex_[v]];
  y_.resize(n);
}

// z = (P L D L' P')^{-1} r, restricted to the current unknowns.
void Flow::applyPreconditioner(const Eigen::VectorXd& r, Eigen::VectorXd& z) {
  ++R_.profile.solves;
  const int n = int(y_.size());
  std::fill(y_.begin(), y_.end(), 0.0);
  for (int v = 0; v < T_.nV; ++v)
    if (free_[v] >= 0) y_[slot_[v]] = r[free_[v]];
  double* y = y_.data();
  const int* S = lStart_.data();
  const int* I = lRow_.data();
  const float* X = lVal_.data();
  for (int j = 0; j < n; ++j) {
    const double yj = y[j];
    if (yj != 0.0)
      for (int p = S[j]; p < S[j + 1]; ++p) y[I[p]] -= double(X[p]) * yj;
  }
  for (int j = 0; j < n; ++j) y[j] *= dInv_[j];
  for (int j = n - 1; j >= 0; --j) {
    double yj = y[j];
    for (int p = S[j]; p < S[j + 1]; ++p) yj -= double(X[p]) * y[I[p]];
    y[j] = yj;
  }
  z.resize(nFree_);
  for (int v = 0; v < T_.nV; ++v)
    if (free_[v] >= 0) z[free_[v]] = y[slot_[v]];
}

// Preconditioned conjugate gradients (Hestenes–Stiefel 1952) for L x = b from x = 0: every
// iterate is a descent direction of the convex energy (b . x_k = x_k' L x_k > 0).
bool Flow::pcg(const Eigen::VectorXd& b, Eigen::VectorXd& x, double tol, int maxIt) {
  x.setZero(nFree_);
  Eigen::VectorXd r = b, z, p, q;
  const double bn = b.norm();
  if (!(bn > 0)) return true;
  applyPreconditioner(r, z);
  p = z;
  double rz = r.dot(z);
  for (int k = 0; k < maxIt; ++k) {
    applyL(p, q);
    const double pq = p.dot(q);
    if (!(pq > 0)) return false;
    const double a = rz / pq;
    x += a * p;
    r -= a * q;
    if (r.norm() <= tol * bn) return true;
    applyPreconditioner(r, z);
    const double rz2 = r.dot(z);
    p = z + (rz2 / rz) * p;
    rz = rz2;
  }
  return false;
}

// (L - dKbar/du) x = b by GMRES (Saad–Schultz 1986), left-preconditioned with the factor:
// the exact Newton step when the (circle) targets move with u.
bool Flow::gmres(const Eigen::VectorXd& b, Eigen::VectorXd& x, double tol, int maxIt) {
  Eigen::VectorXd r0;
  applyPreconditioner(b, r0);
  const double beta = r0.norm();
  x.setZero(nFree_);
  if (!(beta > 0)) return true;
  std::vector<Eigen::VectorXd> V;
  V.push_back(r0 / beta);
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(maxIt + 1, maxIt);
  std::vector<double> cs(maxIt), sn(maxIt);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(maxIt + 1), Av, Bv, w;
  g[0] = beta;
  int m = 0;
  bool converged = false;
  for (int j = 0; j < maxIt; ++j) {
    applyL(V[j], Av);
    applyTargetJacobian(V[j], Bv);
    Av -= Bv;
    applyPreconditioner(Av, w);
    for (int i = 0; i <= j; ++i) {
      H(i, j) = w.dot(V[i]);
      w -= H(i, j) * V[i];
    }
    H(j + 1, j) = w.norm();
    for (int i = 0; i < j; ++i) {
      const double t = cs[i] * H(i, j) + sn[i] * H(i + 1, j);
      H(i + 1, j) = -sn[i] * H(i, j) + cs[i] * H(i + 1, j);
      H(i, j) = t;
    }
    const double r = dmath::hypot(H(j, j), H(j + 1, j));
    cs[j] = H(j, j) / r;
    sn[j] = H(j + 1, j) / r;
    const double hj1 = H(j + 1, j);
    H(j, j) = r;
    H(j + 1, j) = 0;
    g[j + 1] = -sn[j] * g[j];
    g[j] = cs[j] * g[j];
    m = j + 1;
    if (std::fabs(g[j + 1]) <= tol * beta || !(hj1 > 1e-300)) {
      converged = true;
      break;
    }
    V.push_back(w / hj1);
  }
  Eigen::VectorXd y = H.topLeftCorner(m, m).triangularView<Eigen::Upper>().solve(g.head(m));
  for (int i = 0; i < m; ++i) x += y[i] * V[i];
  return converged;
}

// Newton step: L x = b (frozen targets) or (L - dKbar/du) x = b (moving targets), to relative
// tolerance tol. A stale factor that needs more than kFreshFactorIterations is refreshed.
bool Flow::solveNewton(const Eigen::VectorXd& b, Eigen::VectorXd& x, bool moving, double tol) {
  computeWeights();
  bool fresh = false;
  if (!factorCovers()) {
    factor();
    fresh = true;
  }
  for (int attempt = 0; attempt < 2; ++attempt) {
    const int cap = fresh ? 150 : kFreshFactorIterations;
    bool ok;
    {
      ScopedTimer ts(R_.profile.solve);
      ok = moving ? gmres(b, x, tol, cap) : pcg(b, x, tol, cap);
    }
    if (ok || fresh) return ok;
    factor();
    fresh = true;
  }
  return false;
}

FlowResult Flow::run() {
  FlowResult& R = R_;
  setupBoundary();
  R.outerLoop = outer_;
  u_.assign(T_.nV, 0.0);
  const long long flips0 = T_.flips;
  if (!evaluate() && !opt_.flips)
    fail(Code::NotConverged, Stage::Flatten, "flatten: the input violates the triangle inequality");
  auto maxAbs = [](const std::vector<double>& g) {
    double m = 0.0;
    for (double x : g) m = std::max(m, std::fabs(x));
    return m;
  };
  double err = maxAbs(grad_);
  const double err0 = std::max(err, opt_.tolerance * 10);
  R.residuals.push_back(err);
  double reported = 0.0;
  Eigen::VectorXd rhs, delta;
  std::vector<double> uOld;
  bool exactMode = false;
  int exactFailures = 0;
  if (circle_) {
    exactMode = true;
    setGauge(3);
    gatherGradient();  // same u: only the unknowns changed
    err = maxAbs(grad_);
  }
  while (err > opt_.tolerance) {
    if (R.iterations >= opt_.maxIterations)
      fail(Code::IterationLimit, Stage::Flatten,
           "flatten: Newton did not reach the tolerance in " + std::to_string(opt_.maxIterations) + " iterations (error " + std::to_string(err) + ")");
    if (progress_) {
      const double fr = std::clamp(dmath::log(err0 / err) / dmath::log(err0 / opt_.tolerance), 0.0, 0.99);
      reported = std::max(reported, fr);
      if (!progress_(Stage::Flatten, 0.8 * reported)) fail(Code::Cancelled, Stage::Flatten, "flatten: cancelled");
    }
    rhs.resize(nFree_);
    for (int i = 0; i < nFree_; ++i) rhs[i] = -grad_[i];
    // Moving (circle) targets: the exact Newton step (GMRES on L - dKbar/du) converges
    // quadratically but needs the Möbius gauge (3 pins); far from the solution its residual
    // line search may stall, and then Newton with frozen targets (1 pin, a line search on the
    // convex energy) takes over until the error is small.
    const bool movingTargets = exactMode;
    solveNewton(rhs, delta, movingTargets, std::clamp(err, 1e-12, 1e-2));
    double g0 = 0.0;
    for (int i = 0; i < nFree_; ++i) g0 += grad_[i] * grad_[i];
    double d0 = 0.0;
    for (int i = 0; i < nFree_; ++i) d0 += grad_[i] * delta[i];
    if (!movingTargets && (!std::isfinite(d0) || d0 >= 0.0))
      fail(Code::NotConverged, Stage::Flatten,
           "flatten: the Hessian lost positive definiteness at error " + std::to_string(err) +
               " (boundary triangles degenerate: boundary edges cannot be flipped; the boundary targets may be infeasible)");
    uOld = u_;
    double t = 1.0;
    int halvings = 0;
    bool restart = false;
    for (;;) {
      for (int v = 0; v < T_.nV; ++v)
        if (free_[v] >= 0) u_[v] = uOld[v] + t * delta[free_[v]];
      const bool ok = evaluate();
      // Line search on the exact directional derivative phi'(t) = grad(u + t d) . d of the
      // convex energy (the energy itself, with Lobachevsky's function, is not evaluated):
      // accept when phi'(t) <= 1/2 |phi'(0)| (curvature condition; energy decrease estimated by
      // the trapezoid rule, exact for the quadratic model).
      // With moving (circle) targets the system is no gradient: sufficient decrease of the
      // residual norm instead.
      double d1 = 0.0, g1 = 0.0;
      for (int i = 0; i < nFree_; ++i) {
        d1 += grad_[i] * delta[i];
        g1 += grad_[i] * grad_[i];
      }
      if (movingTargets ? (ok && std::isfinite(g1) && std::sqrt(g1) <= (1 - 1e-4 * t) * std::sqrt(g0))
                        : (ok && std::isfinite(d1) && d1 <= -0.5 * d0))
        break;
      if (movingTargets && halvings >= 8) {
        u_ = uOld;
        exactMode = false;
        ++exactFailures;
        setGauge(1);
        evaluate();
        restart = true;
        break;
      }
      if (++halvings > opt_.maxHalvings) {
        u_ = uOld;
        fail(Code::NotConverged, Stage::Flatten,
             std::string("flatten: line search stalled at error ") + std::to_string(err) +
                 (opt_.flips ? "" : " (flips disabled: the triangle inequality breaks)"));
      }
      t *= 0.5;
    }
    if (restart) {
      err = maxAbs(grad_);
      continue;
    }
    ++R.iterations;
    R.steps.push_back(t);
    err = maxAbs(grad_);
    if (circle_ && !exactMode && exactFailures < 3 && err < 1e-3) {
      exactMode = true;
      setGauge(3);
      gatherGradient();
      err = maxAbs(grad_);
    }
    R.residuals.push_back(err);
  }
  if (progress_ && !progress_(Stage::Flatten, 0.8)) fail(Code::Cancelled, Stage::Flatten, "flatten: cancelled");
  // Report the error over every vertex with a target, pinned gauge vertices included.
  R.maxError = 0.0;
  for (int v = 0; v < T_.nV; ++v)
    if (!(opt_.boundary == BoundaryCondition::Free && T_.boundaryVertex[v] && std::find(T_.loops[outer_].begin(), T_.loops[outer_].end(), v) != T_.loops[outer_].end()))
      R.maxError = std::max(R.maxError, std::fabs(K_[v] - Kbar_[v]));
  if (!(R.maxError <= opt_.tolerance)) {
    // The free unknowns converged but an equation held by the gauge did not (the pinned vertices
    // of the Möbius gauge): in exact arithmetic it holds automatically, so round-off decided.
    const std::string why = scaleDiagnosis(T_, u_, opt_.boundary);
    if (!why.empty())
      fail(Code::NumericalFailure, Stage::Flatten, "flatten: the gauge's pinned vertices keep a curvature error of " + std::to_string(R.maxError) + ": " + why);
    char buf[160];
    std::snprintf(buf, sizeof buf, "flatten: the curvature error at the gauge's pinned vertices is %.2e (tolerance %.1e)", R.maxError,
                  opt_.tolerance);
    fail(Code::NotConverged, Stage::Flatten, buf);
  }
  double sumK = 0.0;
  for (double k : K_) sumK += k;
  const double chi = double(T_.nV) - T_.nE + T_.nF;
  R.gaussBonnetError = std::fabs(sumK - 2 * kPi * chi);
  R.flips = T_.flips - flips0;
  R.u = u_;
  R.Kbar = Kbar_;
  return std::move(R_);
}

}  // namespace

int computeAngles(const IT& T, const std::vector<double>& u, std::vector<double>& angle) {
  angle.resize(size_t(3) * T.nF);
  int bad = 0;
  for (int f = 0; f < T.nF; ++f) {
    bool valid;
    faceAngles(T, f, u, &angle[3 * f], &valid);
    bad += !valid;
  }
  return bad;
}

std::vector<double> vertexCurvature(const IT& T, const std::vector<double>& angle) {
  std::vector<double> sum(T.nV, 0.0);
  for (int h = 0; h < 3 * T.nF; ++h) sum[T.vert[IT::prev(h)]] += angle[h];
  for (int v = 0; v < T.nV; ++v) sum[v] = (T.boundaryVertex[v] ? kPi : 2 * kPi) - sum[v];
  return sum;
}

long long flipToDelaunay(IT& T, const std::vector<double>& u, long long maxFlips, bool euclidean) {
  std::vector<double> angle;
  std::vector<char> valid;
  return flipToDelaunayWithAngles(T, u, maxFlips, euclidean, angle, valid);
}

bool isDelaunay(const IT& T, const std::vector<double>& u) {
  for (int e = 0; e < T.nE; ++e)
    if (T.canFlip(e) && !edgeIsDelaunay(T, e, u, 1e-9)) return false;
  return true;
}

FlowResult runRicciFlow(IT& T, const FlowOptions& options, const ProgressFn& progress) {
  if (!(options.tolerance > 0.0) || options.maxIterations < 1 || options.maxHalvings < 1)
    fail(Code::InvalidArgument, Stage::Flatten, "flatten: tolerance must be > 0 and iteration caps >= 1");
  Flow flow(T, options, progress);
  return flow.run();
}

}  // namespace conformesh::conformal
