#include "conformal/layout.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "conformal/triangle_geometry.h"
#include "planar/predicates.h"
#include "core/detmath.h"

namespace conformesh::conformal {

namespace {
using IT = IntrinsicTriangulation;

int centralFace(const IT& T) {
  // Hop distance of vertices from the boundary, over the edges of T.
  std::vector<std::vector<int>> adj(T.nV);
  for (int h = 0; h < 3 * T.nF; ++h) adj[T.vert[h]].push_back(T.tip(h));
  std::vector<int> dist(T.nV, -1), queue;
  for (int v = 0; v < T.nV; ++v)
    if (T.boundaryVertex[v]) {
      dist[v] = 0;
      queue.push_back(v);
    }
  for (size_t q = 0; q < queue.size(); ++q)
    for (int w : adj[queue[q]])
      if (dist[w] < 0) {
        dist[w] = dist[queue[q]] + 1;
        queue.push_back(w);
      }
  int best = 0, bestScore = -1;
  for (int f = 0; f < T.nF; ++f) {
    const int s = std::min(dist[T.vert[3 * f]], std::min(dist[T.vert[3 * f + 1]], dist[T.vert[3 * f + 2]]));
    if (s > bestScore) {
      bestScore = s;
      best = f;
    }
  }
  return best;
}

double orient(const double* a, const double* b, const double* c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

// Whether the closed segments ab and cd share a point, with exact orientation signs: a proper
// crossing, or an endpoint of one on the other (touching, collinear overlap). Disjoint collinear
// segments (the sides of a long straight boundary) do not intersect.
bool segmentsIntersect(const double* a, const double* b, const double* c, const double* d) {
  const double o1 = planar::orient2d(a, b, c), o2 = planar::orient2d(a, b, d);
  const double o3 = planar::orient2d(c, d, a), o4 = planar::orient2d(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return true;
  // r on the line through p and q: is it on the segment?
  auto onSegment = [](const double* p, const double* q, const double* r) {
    return std::min(p[0], q[0]) <= r[0] && r[0] <= std::max(p[0], q[0]) && std::min(p[1], q[1]) <= r[1] &&
           r[1] <= std::max(p[1], q[1]);
  };
  return (o1 == 0 && onSegment(a, b, c)) || (o2 == 0 && onSegment(a, b, d)) || (o3 == 0 && onSegment(c, d, a)) ||
         (o4 == 0 && onSegment(c, d, b));
}
}  // namespace

std::vector<std::pair<int, int>> segmentCrossings(const std::vector<double>& xy, const std::vector<std::pair<int, int>>& seg) {
  if (seg.size() < 2) return {};
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  for (const auto& s : seg)
    for (int v : {s.first, s.second})
      for (int k = 0; k < 2; ++k) {
        lo[k] = std::min(lo[k], xy[2 * v + k]);
        hi[k] = std::max(hi[k], xy[2 * v + k]);
      }
  const int n = int(std::ceil(std::sqrt(double(seg.size()))));
  const double w = std::max(hi[0] - lo[0], hi[1] - lo[1]) / n * (1 + 1e-9) + 1e-300;
  std::vector<std::vector<int>> cells(size_t(n) * n);
  auto cellOf = [&](double x, int k) { return std::clamp(int((x - lo[k]) / w), 0, n - 1); };
  for (size_t i = 0; i < seg.size(); ++i) {
    const double *a = &xy[2 * seg[i].first], *b = &xy[2 * seg[i].second];
    const int x0 = cellOf(std::min(a[0], b[0]), 0), x1 = cellOf(std::max(a[0], b[0]), 0);
    const int y0 = cellOf(std::min(a[1], b[1]), 1), y1 = cellOf(std::max(a[1], b[1]), 1);
    for (int x = x0; x <= x1; ++x)
      for (int y = y0; y <= y1; ++y) cells[size_t(y) * n + x].push_back(int(i));
  }
  std::vector<std::pair<int, int>> hits;
  for (const auto& cell : cells)
    for (size_t p = 0; p < cell.size(); ++p)
      for (size_t q = p + 1; q < cell.size(); ++q) {
        const auto &s = seg[cell[p]], &t = seg[cell[q]];
        if (s.first == t.first || s.first == t.second || s.second == t.first || s.second == t.second) continue;
        if (segmentsIntersect(&xy[2 * s.first], &xy[2 * s.second], &xy[2 * t.first], &xy[2 * t.second]))
          hits.emplace_back(std::min(cell[p], cell[q]), std::max(cell[p], cell[q]));
      }
  std::sort(hits.begin(), hits.end());
  hits.erase(std::unique(hits.begin(), hits.end()), hits.end());
  return hits;
}

std::string scaleDiagnosis(const IT& T, const std::vector<double>& u, BoundaryCondition boundary) {
  double area = 0.0, minEdge = std::numeric_limits<double>::infinity();
  for (int f = 0; f < T.nF; ++f) {
    double lam[3], ang[3];
    for (int k = 0; k < 3; ++k) lam[k] = T.scaledLambda(3 * f + k, u);
    anglesFromLogLengths(lam, ang);
    area += 0.5 * dmath::exp(0.5 * (lam[1] + lam[2])) * dmath::sin(ang[0]);  // angle 0 lies between edges 1, 2
    for (int k = 0; k < 3; ++k) minEdge = std::min(minEdge, dmath::exp(0.5 * lam[k]));
  }
  const double ratio = minEdge / std::sqrt(area);
  if (ratio >= kMinRelativeEdgeLength) return "";
  double umin = std::numeric_limits<double>::infinity(), umax = -umin;
  for (double x : u) {
    umin = std::min(umin, x);
    umax = std::max(umax, x);
  }
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "the %s map scales areas by factors e^{2u} spanning %.1e; its shortest edge is %.1e times the domain "
                "size, beyond what double-precision coordinates resolve away from the layout's origin: %s",
                boundaryName(boundary), dmath::exp(2.0 * (umax - umin)), ratio,
                boundary == BoundaryCondition::Free ? "split the patch where it narrows" : "use the free boundary (u = 0), or split the patch where it narrows");
  return buf;
}

LayoutResult layoutFlat(const IT& T, const std::vector<double>& u) {
  LayoutResult R;
  R.xy.assign(2 * size_t(T.nV), 0.0);
  std::vector<char> placed(T.nV, 0), visited(T.nF, 0);
  auto len = [&](int h) { return dmath::exp(0.5 * T.scaledLambda(h, u)); };
  // Place the vertex opposite halfedge h (whose endpoints are placed) in h's face.
  auto placeThird = [&](int h) {
    const int a = T.vert[h], b = T.tip(h), c = T.vert[IT::prev(h)];
    if (placed[c]) return;
    double lam[3] = {T.scaledLambda(3 * (h / 3), u), T.scaledLambda(3 * (h / 3) + 1, u), T.scaledLambda(3 * (h / 3) + 2, u)};
    double ang[3];
    anglesFromLogLengths(lam, ang);
    const double thetaA = ang[IT::next(h) % 3];  // angle at a, opposite b->c
    const double lca = len(IT::prev(h));
    const double dx = R.xy[2 * b] - R.xy[2 * a], dy = R.xy[2 * b + 1] - R.xy[2 * a + 1];
    const double dl = dmath::hypot(dx, dy);
    const double ex = dx / dl, ey = dy / dl;
    const double x = lca * dmath::cos(thetaA), y = lca * dmath::sin(thetaA);
    R.xy[2 * c] = R.xy[2 * a] + x * ex - y * ey;
    R.xy[2 * c + 1] = R.xy[2 * a + 1] + x * ey + y * ex;
    placed[c] = 1;
  };
  const int f0 = centralFace(T);
  {
    const int h = 3 * f0, a = T.vert[h], b = T.tip(h);
    placed[a] = placed[b] = 1;
    R.xy[2 * b] = len(h);
    placeThird(h);
  }
  std::vector<int> queue = {f0};
  visited[f0] = 1;
  for (size_t q = 0; q < queue.size(); ++q) {
    const int f = queue[q];
    for (int k = 0; k < 3; ++k) {
      const int t = T.twin[3 * f + k];
      if (t < 0 || visited[t / 3]) continue;
      visited[t / 3] = 1;
      placeThird(t);
      queue.push_back(t / 3);
    }
  }
  for (int f = 0; f < T.nF; ++f) {
    const double* p0 = &R.xy[2 * T.vert[3 * f]];
    const double* p1 = &R.xy[2 * T.vert[3 * f + 1]];
    const double* p2 = &R.xy[2 * T.vert[3 * f + 2]];
    if (!(orient(p0, p1, p2) > 0.0)) ++R.invertedTriangles;
  }
  for (int e = 0; e < T.nE; ++e) {
    const int h = T.edgeHalf[e], a = T.vert[h], b = T.tip(h);
    const double l = len(h);
    const double d = dmath::hypot(R.xy[2 * a] - R.xy[2 * b], R.xy[2 * a + 1] - R.xy[2 * b + 1]);
    R.maxEdgeLengthError = std::max(R.maxEdgeLengthError, std::fabs(d - l) / l);
  }
  std::vector<std::pair<int, int>> seg;
  for (const auto& loop : T.loops)
    for (size_t i = 0; i < loop.size(); ++i) seg.emplace_back(loop[i], loop[(i + 1) % loop.size()]);
  for (const auto& [i, j] : segmentCrossings(R.xy, seg))
    R.crossingEdges.push_back({seg[i].first, seg[i].second, seg[j].first, seg[j].second});
  R.boundaryCrossings = int(R.crossingEdges.size());
  return R;
}

}  // namespace conformesh::conformal
