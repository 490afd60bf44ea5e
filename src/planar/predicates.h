// conformesh — robust planar predicates (stage refine).
//
// Exact-sign orient2d and incircle: a floating-point evaluation with a forward error bound
// (the "filter"), and when the bound cannot certify the sign, an exact evaluation in
// floating-point expansion arithmetic. Both follow J. R. Shewchuk, "Adaptive Precision
// Floating-Point Arithmetic and Fast Robust Geometric Predicates", Discrete & Computational
// Geometry 18(3), 1997 (error bounds of section 4.3; expansion sum / scale algorithms of
// section 2). The implementation here is our own. Inputs must be finite doubles; the sign is
// exact for every finite input whose intermediate exact products do not overflow or
// underflow (coordinates with |x| in roughly [1e-140, 1e140]).
//
// predicates.cpp is compiled with -ffp-contract=off: a fused multiply-add would break the
// two-product and error-bound reasoning.
#pragma once

namespace conformesh::planar {

//! Sign-exact orientation: > 0 if a, b, c are counter-clockwise, < 0 clockwise, 0 collinear.
//! The magnitude approximates twice the signed area of triangle abc.
double orient2d(const double* a, const double* b, const double* c);

//! Sign-exact in-circle test: > 0 if d lies strictly inside the circle through a, b, c
//! (a, b, c counter-clockwise), < 0 outside, 0 cocircular. Sign flips if abc is clockwise.
double incircle(const double* a, const double* b, const double* c, const double* d);

//! Number of calls that needed the exact stage, per thread (diagnostics for tests and benchmarks).
struct PredicateStats {
  unsigned long long orientExact = 0;
  unsigned long long incircleExact = 0;
};
PredicateStats& predicateStats();

}  // namespace conformesh::planar
