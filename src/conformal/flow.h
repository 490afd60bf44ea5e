// conformesh — the discrete Ricci flow's solver state (internal to src/conformal): the Newton
// iteration of ricci_flow.cpp and its linear systems (flow_solve.cpp) share it.
#pragma once

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <chrono>
#include <vector>

#include "conformal/ricci_flow.h"

namespace conformesh::conformal::detail {

using Clock = std::chrono::steady_clock;

// Adds the wall time of its scope to a counter (phase profile of the flow).
struct ScopedTimer {
  double& acc;
  Clock::time_point t0 = Clock::now();
  explicit ScopedTimer(double& a) : acc(a) {}
  ~ScopedTimer() { acc += std::chrono::duration<double>(Clock::now() - t0).count(); }
};

class Flow {
 public:
  Flow(IntrinsicTriangulation& T, const FlowOptions& o, const ProgressFn& p) : T_(T), opt_(o), progress_(p) {}
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

  IntrinsicTriangulation& T_;
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

}  // namespace conformesh::conformal::detail
