// conformesh — the one table of remesh()'s options and the one table of its report's fields.
//
// RemeshOptions and RemeshReport (conformesh/remesh.h) are declared from these rows; the embind glue
// (bindings/remesh.cpp) converts them and exports them (remeshSchema()), the native CLI
// (src/cli/cmd_remesh.cpp) and the package CLI (bindings/src/cli.ts, from remeshSchema()) take
// their flags, help and JSON from them, and tests/js/schema.test.ts checks the TypeScript types
// (bindings/src/schema.ts) against the module's export and both CLIs' help and JSON.
//
// The same name everywhere: the C++ field, the JS option or report key, the JSON key.
// One sentinel convention for lengths and tolerances: < 0 derives the value (from the matching
// *Rel option or from the other sizes), 0 switches the feature off where off has a meaning.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>


namespace conformesh {

//! The boundary condition of a patch's flattening (conformal/ricci_flow.h): a round disk, u = 0 on
//! the boundary (isometric on developable patches), or corners keeping their 3D angle.
enum class BoundaryCondition { Circle, Free, Corners };

//! The option kinds: how a binding or a CLI reads a value (a count saturates at SIZE_MAX).
using Boundary = BoundaryCondition;
using Count = size_t;

//! The name of a boundary condition in options, flags and JSON.
inline const char* boundaryKey(Boundary b) {
  return b == Boundary::Circle ? "circle" : b == Boundary::Corners ? "corners" : "free";
}
//! Sets b to the condition named s (boundaryKey's names); false for any other name.
inline bool parseBoundary(const std::string& s, Boundary& b) {
  for (Boundary c : {Boundary::Free, Boundary::Corners, Boundary::Circle})
    if (s == boundaryKey(c)) return b = c, true;
  return false;
}

// X(type, name, default, lo, hi, flag, value, help)
//
// lo/hi: the range the bindings accept (remesh() itself rejects what it cannot use).
// flag: the CLI flag; a bool whose flag starts with "--no-" sets false, any other sets true;
// "" for an option only the library API has (it shapes the returned arrays, which the CLI does
// not write).
#define CONFORMESH_REMESH_OPTIONS(X)                                                                                    \
  X(double, minAngle, 30.0, 0, 35, "--min-angle", "DEG",                                                                \
    "angle bound of every triangle outside exempt input corners, degrees in [0, 35]")                                   \
  X(double, targetEdgeLength, -1.0, -1e308, 1e308, "--edge-length", "L",                                                \
    "target edge length in flat regions (input units); < 0: --edge-length-rel")                                         \
  X(double, targetEdgeLengthRel, 0.01, 0, 1e308, "--edge-length-rel", "R",                                              \
    "target edge length as a fraction of the bounding-box diagonal")                                                    \
  X(double, chordTolerance, -1.0, -1e308, 1e308, "--chord-tol", "T",                                                    \
    "chord deviation bound of the curvature sizing (input units); < 0: --chord-tol-rel times the diagonal; 0: off")     \
  X(double, chordToleranceRel, 1e-3, 0, 1e308, "--chord-tol-rel", "R",                                                  \
    "chord deviation bound as a fraction of the bounding-box diagonal, when --chord-tol < 0")                           \
  /* a cone's tip is cut off linearly in the size, not quadratically (features/sizing.h); error-driven remeshing turns    \
     it on for its next attempt when one exceeds the bound (remesh/max_error.h) */                                      \
  X(bool, coneTips, false, 0, 1, "--cone-tips", "",                                                                     \
    "hold the chord deviation at cone tips too: sizes there bounded by the tolerance over the tip's slope")            \
  /* error-driven: the sizes grow as large as the chord error, the curvature and the angle bound allow; the report's    \
     measured Hausdorff distance is at most this, else IterationLimit (remesh/max_error.h) */                           \
  X(double, maxError, -1.0, -1e308, 1e308, "--max-error", "D",                                                          \
    "error-driven remeshing: the largest Hausdorff distance to the input (input units); the sizes grow as far "        \
    "as it allows; < 0: --max-error-rel; 0: off")                                                                       \
  X(double, maxErrorRel, 0.0, 0, 1e308, "--max-error-rel", "R",                                                         \
    "--max-error as a fraction of the bounding-box diagonal; 0: off")                                                   \
  X(double, gradation, 1.5, 1, 1e308, "--gradation", "G", "bound on the ratio of neighbouring edge lengths, > 1")       \
  X(double, minEdgeLength, -1.0, -1e308, 1e308, "--min-edge-length", "L",                                               \
    "shortest edge the sizing allows (input units); < 0: a tenth of the target edge length, or under an error bound "   \
    "the chord tolerance where smaller")                                                                                \
  X(double, maxEdgeLength, -1.0, -1e308, 1e308, "--max-edge-length", "L",                                               \
    "longest edge the sizing allows (input units); < 0: the target edge length")                                        \
  X(double, featureAngle, 40.0, 0, 180, "--feature-angle", "DEG",                                                       \
    "edges whose dihedral angle exceeds this (degrees) may be features")                                                \
  X(double, cornerTurn, 50.0, 0, 180, "--corner-turn", "DEG",                                                           \
    "a feature curve turning by more than this (degrees) at a vertex gets a corner there")                              \
  /* creases only in chains that stand out of their neighbourhood (features/creases.h); user feature edges stay */      \
  X(double, minFeatureLength, -1.0, -1e308, 1e308, "--min-feature-length", "L",                                         \
    "shortest chain of sharp edges kept as a crease (input units); < 0: twice the edge length; 0: all")               \
  /* a strip far narrower than the output edges (a CAD chamfer) is otherwise meshed below the sizing's floor            \
     (docs/decisions/0007-narrow-strips.md) */                                                                          \
  X(double, minPatchWidth, 0.0, -1e308, 1e308, "--min-patch-width", "W",                                                \
    "merge patches narrower than this (2 area / perimeter, input units) into a neighbour; < 0: half the "               \
    "smallest edge; 0: off")                                                                                            \
  /* a crease ending inside a smooth region need not cut it (docs/decisions/0043-inner-creases.md) */                  \
  X(bool, innerCreases, true, 0, 1, "--no-inner-creases", "",                                                          \
    "continue a crease that ends inside a region until it closes the region off (else a polyline inside its patch)")   \
  /* when a layout fails (overlaps itself, or loses precision) the others follow: free, corners, circle */              \
  X(Boundary, boundary, Boundary::Free, 0, 0, "--boundary", "free|corners|circle",                                      \
    "the boundary condition each patch's flattening tries first")                                                       \
  /* the planar sizing would otherwise span a huge range and the flow's layout lose precision */                        \
  X(double, maxScaleRatio, 50.0, 1, 1e308, "--max-scale-ratio", "R",                                                    \
    "split a patch whose conformal scale factor ratio (max/min) exceeds this")                                          \
  /* the rounds also stop after two in a row that do not beat the best one; a stitch defect left at the cap gets two    \
     more rounds in which its patches keep their boundary */                                                            \
  X(int, maxCertificateRounds, 6, 0, 100, "--max-certificate-rounds", "N",                                              \
    "cap on the rounds of the 3D angle certificate (patches re-meshed finer where a triangle is below the bound)")      \
  X(bool, optimize, true, 0, 1, "--no-optimize", "", "skip the optimization (vertex moves and flips judged in 3D)")     \
  X(int, optimizeIterations, 2, 0, 1000, "--optimize-iterations", "N",                                                  \
    "passes of the optimization (a cap; one more above a 30 degree bound), an integer >= 0")                            \
  X(double, optimizeTolerance, 1e-3, 0, 1e308, "--optimize-tolerance", "T",                                             \
    "stop optimizing when a pass gains less than this fraction of the mean min angle")                                  \
  X(bool, patches, false, 0, 1, "", "", "return every patch in the plane and the patch of every output triangle")       \
  /* attribute seams (mesh/mesh_attributes.h) are kept as feature curves, so texture charts stay whole; every output    \
     corner's value is the input's interpolated at its pull-back point (remesh/carry_attributes.h) */                   \
  X(bool, attributes, true, 0, 1, "--no-attributes", "",                                                                \
    "drop the input's uvs, normals, colours and other vertex data (else interpolated onto the output, seams kept)")     \
  X(bool, surfacePoints, false, 0, 1, "", "",                                                                           \
    "return every output corner's point on the input even for an input without attributes")                             \
  X(bool, computeHausdorff, true, 0, 1, "--no-hausdorff", "",                                                           \
    "leave the Hausdorff distance out of the report (it costs time on big meshes)")                                     \
  X(Count, hausdorffSamples, 50000, 1, 1e8, "--hausdorff-samples", "N",                                                 \
    "sample points of the report's Hausdorff distance")                                                                 \
  /* core/parallel_for.h; always 1 in the WebAssembly build */                                                          \
  X(int, threads, 0, 0, 1024, "--threads", "N",                                                                         \
    "threads over the patches and the report's distances; 0: the hardware's concurrency; the output is the "            \
    "same for any count")                                                                                               \
  /* limits (remesh/limits.h): predicted from the sizing field before flattening, checked after refinement; 0 is        \
     InvalidArgument, not "no limit"; 32-bit indices throughout; a WASM module has at most 4 GiB */                     \
  X(Count, maxVertices, Count(16) << 20, 0, 1e18, "--max-vertices", "N",                                                \
    "fail with TooLarge when the output would have more vertices")                                                      \
  X(Count, maxTriangles, Count(32) << 20, 0, 1e18, "--max-triangles", "N",                                              \
    "fail with TooLarge when the output would have more triangles")                                                     \
  X(double, maxMemoryBytes, 3.0 * double(Count(1) << 30), 0, 1e308, "--max-memory", "BYTES",                            \
    "fail with TooLarge when the run would need more heap than this")                                                   \
  /* the topology check: the input's components, boundary loops and Euler characteristic, and manifold */               \
  X(bool, keepDefectiveOutput, false, 0, 1, "--keep-defective", "",                                                     \
    "write the output even when its topology is not the input's (still exit 1)")                                        \
  X(bool, forceTopologyDefect, false, 0, 1, "--force-topology-defect", "",                                              \
    "break the output on purpose, to test the topology check")

// X(type, name, initial value): an exempt corner (ExemptCorner, remesh/remesh.h).
#define CONFORMESH_EXEMPT_CORNER(X) \
  X(uint32_t, vertex, 0) X(uint32_t, outputVertex, 0) X(double, angle, 0) X(std::vector<uint32_t>, triangles, {})

// X(type, name, initial value): the report's fields, in the order the JS object and the JSON give them.
// Angles in degrees over all triangles; pct*: percent of the triangles (pctMinAtLeast40: whose
// smallest angle is >= 40 degrees); *OutsideExempt: over the triangles no exempt corner lists;
// hausdorffRel: two-sided, over the input's bounding-box diagonal (-1: not computed);
// maxDistanceToInputRel: the largest output vertex distance to the input over the diagonal;
// delaunayFraction: interior edges that are Delaunay in 3D; droppedFeatureEdges: sharp edges found
// not to be creases (minFeatureLength); seamEdges: input edges kept as curves for being attribute
// seams; flowIterations: Newton iterations per patch; patchSplitsForScale: geodesic Voronoi splits
// of patches whose flattening failed or spread its scale past maxScaleRatio; sinkCuts: patches cut
// in two through the point their scale sank to or a spike tip (features/sink_cuts.h); patchJoins:
// narrow patches joined to a neighbour once flattened, the joins kept (remesh/flatten_patches.cpp);
// optimizeMoves, optimizeFlips: accepted by the
// optimization (moves include curve-sample slides); optimizeSplits: vertices the optimization added
// where its moves and flips left a triangle below the bound (remesh/split_below_bound.h);
// optimizeCollapses: edges the optimization collapsed toward regular valences (above a 30° bound,
// remesh/optimize.h); repairMoves: free vertices moved where the
// certificate left a triangle below the bound (remesh/repair.h); estimatedTriangles: the output size
// predicted from the sizing field and the flattened patches' widths before refinement (remesh/limits.h); topologyPreserved: false only with
// keepDefectiveOutput; seconds: per stage (conformesh/stages.h).
#define CONFORMESH_REMESH_REPORT(X)                                                                                     \
  X(size_t, inputTriangles, 0) X(size_t, inputVertices, 0) X(size_t, triangles, 0) X(size_t, vertices, 0)               \
  X(double, minAngle, 0) X(double, maxAngle, 0) X(double, meanMinAngle, 0)                                              \
  X(double, pctBelow20, 0) X(double, pctBelow26, 0) X(double, pctBelow30, 0)                                            \
  X(double, pctMinAtLeast40, 0) X(double, pctMinAtLeast50, 0)                                                           \
  X(double, minAngleOutsideExempt, 0) X(size_t, trianglesBelowBoundOutsideExempt, 0)                                    \
  X(std::vector<ExemptCorner>, exemptCorners, {})                                                                       \
  X(double, hausdorffRel, -1) X(double, maxDistanceToInputRel, 0)                                                       \
  X(double, meanEdgeLength, 0) X(double, targetEdgeLength, 0) X(double, delaunayFraction, 0)                            \
  X(size_t, featureCurves, 0) X(size_t, featureCurvesKept, 0) X(size_t, sharpEdges, 0) X(size_t, cutEdges, 0)           \
  X(size_t, droppedFeatureEdges, 0) X(size_t, seamEdges, 0)                                                             \
  X(size_t, patches, 0) X(size_t, curves, 0) X(size_t, curveSamples, 0)                                                 \
  X(std::vector<int>, flowIterations, {}) X(size_t, patchSplitsForScale, 0) X(size_t, sinkCuts, 0)                       \
  X(size_t, patchJoins, 0)                                                                                              \
  X(int, conformingRounds, 0) X(int, certificateRounds, 0)                                                              \
  X(size_t, optimizeMoves, 0) X(size_t, optimizeFlips, 0) X(size_t, optimizeSplits, 0)                                  \
  X(size_t, optimizeCollapses, 0)                                                                                       \
  X(size_t, repairMoves, 0)                                                                                             \
  X(double, estimatedTriangles, 0) X(bool, topologyPreserved, false)                                                    \
  X(StageSeconds, seconds, {}) X(std::vector<std::string>, warnings, {})

}  // namespace conformesh
