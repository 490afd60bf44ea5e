#include "features/sizing.h"

#include <algorithm>
#include <cmath>
#include <queue>

namespace conformesh::features {

double boundingBoxDiagonal(const EdgeGraph& g) {
  Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  for (const auto& p : g.positions) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  return g.positions.empty() ? 0.0 : norm(hi - lo);
}

namespace {

// Per vertex, the largest of edgeTerm(n, d) over its edges d (n: the unit area-weighted vertex
// normal; 0 where it vanishes).
template <typename EdgeTerm>
std::vector<double> largestOverEdges(const EdgeGraph& g, EdgeTerm edgeTerm) {
  std::vector<Vec3> vn(g.vertexCount);  // area-weighted vertex normals
  for (uint32_t f = 0; f < g.faceCount; ++f) {
    const auto& t = g.faces[f];
    Vec3 n = cross(g.positions[t[1]] - g.positions[t[0]], g.positions[t[2]] - g.positions[t[0]]);
    for (uint32_t v : t) vn[v] = vn[v] + n;
  }
  std::vector<double> out(g.vertexCount, 0.0);
  for (uint32_t v = 0; v < g.vertexCount; ++v) {
    const double ln = norm(vn[v]);
    if (ln == 0) continue;
    const Vec3 n = vn[v] * (1.0 / ln);
    for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k) {
      const Vec3 d = g.positions[g.otherVertex(g.vertexEdgeIds[k], v)] - g.positions[v];
      if (dot(d, d) > 0) out[v] = std::max(out[v], edgeTerm(n, d));
    }
  }
  return out;
}

}  // namespace

std::vector<double> surfaceCurvature(const EdgeGraph& g) {
  return largestOverEdges(g, [](const Vec3& n, const Vec3& d) { return 2.0 * std::abs(dot(n, d)) / dot(d, d); });
}

std::vector<double> surfaceSlope(const EdgeGraph& g) {
  return largestOverEdges(g, [](const Vec3& n, const Vec3& d) { return std::abs(dot(n, d)) / norm(d); });
}

SizingField computeSizing(const EdgeGraph& g, const Segmentation& seg, const SizingOptions& o) {
  SizingField s;
  s.diagonal = boundingBoxDiagonal(g);
  if (!(s.diagonal > 0)) fail(Code::InvalidArgument, Stage::CurveMesh, "the mesh has a zero bounding box");
  s.target = o.targetEdgeLength > 0 ? o.targetEdgeLength : o.targetEdgeLengthRel * s.diagonal;
  if (!(s.target > 0) || !std::isfinite(s.target))
    fail(Code::InvalidArgument, Stage::CurveMesh, "targetEdgeLength must be positive");
  if (s.target < 1e-5 * s.diagonal)
    fail(Code::TooLarge, Stage::CurveMesh, "targetEdgeLength below 1e-5 of the bbox diagonal");
  if (!(o.gradation > 1.0)) fail(Code::InvalidArgument, Stage::CurveMesh, "gradation must be > 1");
  if (!o.vertexSizing.empty() && o.vertexSizing.size() != g.vertexCount)
    fail(Code::InvalidArgument, Stage::CurveMesh, "vertexSizing needs one value per input vertex");
  s.gradation = o.gradation;
  s.minLength = o.minEdgeLength > 0 ? o.minEdgeLength : 0.1 * s.target;
  s.maxLength = o.maxEdgeLength > 0 ? o.maxEdgeLength : s.target;
  if (s.minLength > s.maxLength)
    fail(Code::InvalidArgument, Stage::CurveMesh, "minEdgeLength exceeds maxEdgeLength");
  s.minLength = std::max(s.minLength, 1e-5 * s.diagonal);
  const double tol = o.chordTolerance >= 0 ? o.chordTolerance : o.chordToleranceRel * s.diagonal;

  s.h.assign(g.vertexCount, s.target);
  if (tol > 0) {
    // the caller's, when it gave one per vertex (not copied); else the graph's own
    std::vector<double> ownKappa;
    if (o.surfaceKappa.size() != g.vertexCount) ownKappa = surfaceCurvature(g);
    const std::vector<double>& kappaSurface = o.surfaceKappa.size() == g.vertexCount ? o.surfaceKappa : ownKappa;
    // from v along curve edge e to the first vertex that is no split point (see
    // firstSplitVertex); a split point on a curve has exactly two curve edges
    auto alongCurve = [&](uint32_t v, uint32_t e) {
      uint32_t w = g.otherVertex(e, v);
      for (int step = 0; step < 1 << 20 && w >= o.firstSplitVertex; ++step) {  // hard cap
        uint32_t next = kNone;
        int n = 0;
        for (uint32_t k = g.vertexEdgeStart[w]; k < g.vertexEdgeStart[w + 1]; ++k)
          if (const uint32_t f = g.vertexEdgeIds[k]; seg.isCurveEdge(f) && ++n && f != e) next = f;
        if (n != 2 || next == kNone) break;
        e = next;
        w = g.otherVertex(e, w);
      }
      return w;
    };
    const std::vector<double> slope = o.coneTips ? surfaceSlope(g) : std::vector<double>{};
    for (uint32_t v = 0; v < g.vertexCount; ++v) {
      double kappa = 0;
      uint32_t curveEdges[2], nc = 0;
      bool onlyCuts = true;  // every curve edge at v is a cut: the surface is smooth across them
      for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k)
        if (const uint32_t e = g.vertexEdgeIds[k]; seg.isCurveEdge(e)) {
          onlyCuts = onlyCuts && seg.edgeKind[e] == EdgeKind::Cut;
          if (nc++ < 2) curveEdges[nc - 1] = e;
        }
      // Off the curves and on cuts: the surface's curvature. A cut is no crease, and its
      // polyline's turns (it follows input edges) say nothing about the surface. On feature and
      // boundary curves: the curve's curvature (the output follows the curve).
      if (nc == 0 || onlyCuts) {
        kappa = kappaSurface[v];
        if (!slope.empty() && slope[v] > 0) s.h[v] = std::min(s.h[v], std::sqrt(3.0) * tol / slope[v]);
      } else if (nc == 2 && !seg.vertexCorner[v]) {
        Vec3 a = g.positions[v] - g.positions[alongCurve(v, curveEdges[0])];
        Vec3 b = g.positions[alongCurve(v, curveEdges[1])] - g.positions[v];
        double len = 0.5 * (norm(a) + norm(b));
        if (len > 0) kappa = angleBetween(a, b) / len;
      }
      if (kappa > 0) s.h[v] = std::min(s.h[v], std::sqrt(8.0 * tol / kappa));
    }
    // A bend of θ between two faces that the output spans (no feature curve: a sharp edge that
    // is no crease, a coarse facet's edge, or a cut, which is smooth) leaves an output triangle
    // across it up to (h/2)·sin(θ/2) away: h <= 2·tol / sin(θ/2) at both ends. The vertex
    // curvature above spreads a bend over the input's edge length: far gentler where edges are
    // long.
    for (uint32_t e = 0; e < g.edgeCount(); ++e) {
      if (g.isBoundary(e) || seg.edgeKind[e] == EdgeKind::Feature) continue;
      const double half = 0.5 * angleBetween(g.faceNormal(g.edgeFaces[e][0]), g.faceNormal(g.edgeFaces[e][1]));
      if (!(half > 0)) continue;
      const double h = 2.0 * tol / dmath::sin(half);
      for (uint32_t v : g.edgeVerts[e]) s.h[v] = std::min(s.h[v], h);
    }
  }
  for (uint32_t v = 0; v < g.vertexCount; ++v) {
    if (!o.vertexSizing.empty()) {
      double u = o.vertexSizing[v];
      if (!(u > 0) || !std::isfinite(u))
        fail(Code::InvalidArgument, Stage::CurveMesh, "vertexSizing values must be positive and finite");
      s.h[v] = std::min(s.h[v], u);
    }
    s.h[v] = std::clamp(s.h[v], s.minLength, s.maxLength);
  }
  // gradation: h(w) <= h(v) + (gradation − 1)·|vw|, smallest first (Dijkstra order)
  const double slope = o.gradation - 1.0;
  using Item = std::pair<double, uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> pq;
  for (uint32_t v = 0; v < g.vertexCount; ++v) pq.push({s.h[v], v});
  while (!pq.empty()) {
    auto [h, v] = pq.top();
    pq.pop();
    if (h > s.h[v]) continue;
    for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k) {
      uint32_t e = g.vertexEdgeIds[k];
      uint32_t w = g.otherVertex(e, v);
      double nh = h + slope * g.edgeLength(e);
      if (nh < s.h[w]) {
        s.h[w] = nh;
        pq.push({nh, w});
      }
    }
  }
  return s;
}

}  // namespace conformesh::features
