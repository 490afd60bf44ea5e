#include "remesh/limits.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "features/patch_width.h"

namespace conformesh {
namespace {

// A count or byte figure for messages: "1234567" up to 1e15, else "%.3g".
std::string figure(double x) {
  char buf[32];
  if (x < 1e15) std::snprintf(buf, sizeof buf, "%.0f", std::ceil(x));
  else std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

void requireLimit(double value, const char* name) {
  if (!(value >= 1))
    fail(Code::InvalidArgument, Stage::Api,
         std::string(name) + " must be >= 1 (0 does not mean unlimited: pass a huge value to lift the limit)");
}

// How fast the refinement's sizes grow away from a thin feature, per unit of distance: slower
// than the sizing's gradation lets them (its off-centers grade the band; measured on the rim of a
// thin slab, tests/native/remesh/limits_test.cpp: 0.35 with the 50° off-center apex, 0.38 with
// 45°; docs/decisions/0045).
constexpr double kRefinementGrading = 0.4;

// The part of ∫ 1/h² that the thin features add to the field (see estimateOutput).
double thinFeatureIntegral(const features::EdgeGraph& g, const features::Segmentation& seg,
                           const features::SizingField& sizing) {
  const double k = std::min(sizing.gradation - 1.0, kRefinementGrading);
  const std::vector<std::array<double, 2>> width = features::patchWidths(g, seg, sizing.maxLength);
  double sum = 0;
  for (uint32_t e = 0; e < g.edgeCount(); ++e) {
    const auto& w = width[e];
    const auto& ev = g.edgeVerts[e];
    const double h = std::min(sizing.h[ev[0]], sizing.h[ev[1]]);
    // the edge's own size: the narrower side (a thin strip's neighbour is sampled as finely),
    // kept off zero for a width of zero (two boundary edges through one point)
    const double a = std::max(std::min({h, w[0], w[1]}), sizing.minLength * 1e-3);
    if (!(a < h)) continue;
    const double len = g.edgeLength(e);
    for (int side = 0; side < 2; ++side) {
      if (side == 1 && g.isBoundary(e)) break;
      const double d = std::min((h - a) / k, 0.5 * w[side]);
      sum += len * ((1.0 / a - 1.0 / (a + k * d)) / k - d / (h * h));
    }
  }
  return sum;
}

}  // namespace

OutputEstimate estimateOutput(const features::EdgeGraph& g, const features::Segmentation& seg,
                              const features::SizingField& sizing) {
  const double equilateral = std::sqrt(3.0) / 4.0;
  OutputEstimate e;
  for (uint32_t f = 0; f < g.faceCount; ++f) {
    double invH2 = 0;
    for (uint32_t v : g.faces[f]) invH2 += 1.0 / (3.0 * sizing.h[v] * sizing.h[v]);
    e.triangles += g.faceArea(f) * invH2 / equilateral;
  }
  e.triangles += thinFeatureIntegral(g, seg, sizing) / equilateral;
  e.triangles *= kTrianglesPerEquilateral;
  double boundarySamples = 0;
  for (uint32_t k = 0; k < g.edgeCount(); ++k) {
    if (!g.isBoundary(k)) continue;
    const auto& ev = g.edgeVerts[k];
    boundarySamples += g.edgeLength(k) * 0.5 * (1.0 / sizing.h[ev[0]] + 1.0 / sizing.h[ev[1]]);
  }
  e.vertices = 0.5 * e.triangles + boundarySamples;
  e.bytes = kBytesPerInputTriangle * double(g.faceCount) + kBytesPerOutputTriangle * e.triangles;
  return e;
}

OutputEstimate estimateFromTarget(double area, double target, size_t inputTriangles) {
  OutputEstimate e;
  e.triangles = kTrianglesPerEquilateral * area / (std::sqrt(3.0) / 4.0 * target * target);
  e.vertices = 0.5 * e.triangles;
  e.bytes = kBytesPerInputTriangle * double(inputTriangles) + kBytesPerOutputTriangle * e.triangles;
  return e;
}

void checkOutputEstimate(const OutputEstimate& e, const RemeshOptions& o) {
  requireLimit(double(o.maxTriangles), "maxTriangles");
  requireLimit(double(o.maxVertices), "maxVertices");
  requireLimit(o.maxMemoryBytes, "maxMemoryBytes");
  const std::string hint = " (estimate from the sizing field; raise the target edge length or the limit)";
  if (e.triangles > double(o.maxTriangles))
    fail(Code::TooLarge, Stage::CurveMesh,
         "the output would have about " + figure(e.triangles) + " triangles, above maxTriangles = " +
             figure(double(o.maxTriangles)) + hint);
  if (e.vertices > double(o.maxVertices))
    fail(Code::TooLarge, Stage::CurveMesh,
         "the output would have about " + figure(e.vertices) + " vertices, above maxVertices = " +
             figure(double(o.maxVertices)) + hint);
  if (e.bytes > o.maxMemoryBytes)
    fail(Code::TooLarge, Stage::CurveMesh,
         "remesh would need about " + figure(e.bytes) + " bytes of memory, above maxMemoryBytes = " +
             figure(o.maxMemoryBytes) + hint);
}

void checkOutputCounts(size_t vertices, size_t triangles, const RemeshOptions& o) {
  if (triangles > o.maxTriangles)
    fail(Code::TooLarge, Stage::Stitch,
         "the output has " + std::to_string(triangles) + " triangles, above maxTriangles = " +
             std::to_string(o.maxTriangles) + " (the estimate before refinement was below it)");
  if (vertices > o.maxVertices)
    fail(Code::TooLarge, Stage::Stitch,
         "the output has " + std::to_string(vertices) + " vertices, above maxVertices = " +
             std::to_string(o.maxVertices) + " (the estimate before refinement was below it)");
}

}  // namespace conformesh
