#include "conformal/ricci_flow.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "conformal/flow.h"
#include "conformal/layout.h"
#include "conformal/triangle_geometry.h"
#include "core/detmath.h"

namespace conformesh::conformal {

namespace {

using IT = IntrinsicTriangulation;
using detail::Clock;
using detail::ScopedTimer;

// Newton iterations over which the error must fall by a tenth (else it stalled); man: failing
// patches ran the whole cap of 100 iterations at a constant error, a third of its flattening time.
constexpr int kStallWindow = 10;


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

}  // namespace

namespace detail {

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
    // Targets no metric meets (a cone whose star has a border edge too long for it, with the
    // border's u fixed) leave the convex energy's minimum at infinity: Newton descends ever more
    // slowly. Stop once kStallWindow iterations have not cut the error by a tenth.
    if (R.iterations >= 2 * kStallWindow && err > 0.9 * R.residuals[R.residuals.size() - kStallWindow])
      fail(Code::IterationLimit, Stage::Flatten,
           "flatten: Newton stalled: " + std::to_string(kStallWindow) + " iterations did not cut the error by a tenth (error " +
               std::to_string(err) + ")");
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

}  // namespace detail

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
  detail::Flow flow(T, options, progress);
  return flow.run();
}

}  // namespace conformesh::conformal
