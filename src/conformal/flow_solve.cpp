#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <string>

#include "conformal/flow.h"
#include "conformal/triangle_geometry.h"
#include "core/detmath.h"

// Newton's linear systems of the Ricci flow (see Flow in flow.h).
namespace conformesh::conformal::detail {

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

}  // namespace conformesh::conformal::detail
