// conformesh — attributes carried onto the remeshed surface: locate corners on the input (AABB
// closest point, then the face around it that the corner's triangle enters), interpolate there.
#include "remesh/carry_attributes.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mesh/mesh_attributes.h"
#include "quality/aabb_tree.h"
#include "quality/metrics.h"

namespace conformesh {

namespace {

constexpr uint32_t kNone = UINT32_MAX;
// a point is on an input face when it is this close (relative to the input's bounding-box
// diagonal) to it, no farther than from the closest face
constexpr double kOnSurface = 1e-9;
// faces the walk from a triangle's centroid visits at most before giving up (then the candidate
// face closest to the centroid is taken)
constexpr size_t kMaxWalk = 4096;



// The closest point of input face f to p: its squared distance and barycentric coordinates;
// false for a face with (numerically) zero area.
bool closestOnFace(const MeshBuffers& m, uint32_t f, const Vec3& p, double& d2, double bary[3]) {
  const uint32_t* t = &m.triangles[3 * size_t(f)];
  const Vec3 a = vec3At(m.positions, t[0]), b = vec3At(m.positions, t[1]), c = vec3At(m.positions, t[2]);
  const Vec3 e0 = b - a, e1 = c - a;
  const double d00 = dot(e0, e0), d01 = dot(e0, e1), d11 = dot(e1, e1);
  const double den = d00 * d11 - d01 * d01;  // |e0 × e1|²
  if (!(den > 1e-20 * d00 * d11)) return false;
  const Vec3 q = quality::closestPointOnTriangle(p, a, b, c);
  const Vec3 w = q - a;
  const double d20 = dot(w, e0), d21 = dot(w, e1);
  bary[1] = (d11 * d20 - d01 * d21) / den;
  bary[2] = (d00 * d21 - d01 * d20) / den;
  bary[0] = 1.0 - bary[1] - bary[2];
  const Vec3 r = p - q;
  d2 = dot(r, r);
  return true;
}

}  // namespace

CornerPoints locateCorners(const MeshBuffers& input, const MeshBuffers& output, const std::vector<uint32_t>& vertexHint) {
  const size_t nIn = input.triangleCount(), nvIn = input.vertexCount(), nt = output.triangleCount();
  CornerPoints cp;
  cp.face.assign(3 * nt, kNone);
  cp.barycentric.assign(9 * nt, 0.0);
  if (nt == 0 || nIn == 0) return cp;
  // input faces around each input vertex (compressed rows)
  std::vector<uint32_t> start(nvIn + 1, 0), faces(input.triangles.size());
  for (uint32_t v : input.triangles) ++start[v + 1];
  for (size_t v = 0; v < nvIn; ++v) start[v + 1] += start[v];
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (size_t c = 0; c < input.triangles.size(); ++c) faces[fill[input.triangles[c]]++] = uint32_t(c / 3);
  }
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t v = 0; v < nvIn; ++v)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], input.positions[3 * v + k]), hi[k] = std::max(hi[k], input.positions[3 * v + k]);
  const Vec3 extent = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
  const double slack = kOnSurface * std::sqrt(dot(extent, extent));

  // per output vertex, the input faces its point is on: the closest face (AABB tree) and those
  // around that face's vertices as close, with the barycentric coordinates there
  struct OnFace {
    uint32_t face;
    double d2;
    double bary[3];
  };
  std::vector<uint32_t> onStart(output.vertexCount() + 1, 0);
  std::vector<OnFace> on;
  quality::TriangleMeshDistance dist(input);
  {
    int64_t hint = -1;
    std::vector<OnFace> here;
    for (size_t v = 0; v < output.vertexCount(); ++v) {
      const Vec3 p = vec3At(output.positions, uint32_t(v));
      if (v < vertexHint.size() && vertexHint[v] < nIn) hint = vertexHint[v];
      const quality::ClosestHit h = dist.closest(p, hint);
      here.clear();
      if (h.primitive >= 0) {
        hint = h.primitive;
        const double bound = std::sqrt(h.distanceSquared) + slack;
        for (int k = 0; k < 3; ++k) {
          const uint32_t iv = input.triangles[3 * size_t(h.primitive) + k];
          for (uint32_t i = start[iv]; i < start[iv + 1]; ++i) {
            OnFace o{faces[i], 0, {0, 0, 0}};
            if (std::any_of(here.begin(), here.end(), [&](const OnFace& x) { return x.face == o.face; })) continue;
            if (closestOnFace(input, o.face, p, o.d2, o.bary) && std::sqrt(o.d2) <= bound) here.push_back(o);
          }
        }
        std::sort(here.begin(), here.end(), [](const OnFace& a, const OnFace& b) { return a.d2 < b.d2 || (a.d2 == b.d2 && a.face < b.face); });
        if (here.empty()) here.push_back(OnFace{uint32_t(h.primitive), 0, {1, 0, 0}});  // zero-area faces only
      }
      on.insert(on.end(), here.begin(), here.end());
      onStart[v + 1] = uint32_t(on.size());
    }
  }
  // A vertex on several faces (on an input edge or vertex) that may be on a seam: each corner
  // takes the face its triangle is on. Walk from the input face closest to the triangle's
  // centroid (inside the triangle's side: the seams are output edges) across input edges that
  // are not seams, breadth first, to the first of the vertex's faces.
  const bool sided = std::any_of(input.attributes.begin(), input.attributes.end(), [](const MeshAttribute& a) { return a.perCorner; });
  const std::vector<uint32_t> across = sided ? neighboursWithinCharts(input) : std::vector<uint32_t>();
  std::vector<uint32_t> seen(sided ? nIn : 0, kNone), queue;  // seen: the walk that last visited the face
  uint32_t walk = 0;
  for (size_t t = 0; t < nt; ++t) {
    const uint32_t* tv = &output.triangles[3 * t];
    int64_t anchor = -1;
    Vec3 centroid = {0, 0, 0};
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = tv[c];
      if (onStart[v] == onStart[v + 1]) continue;
      const OnFace* best = &on[onStart[v]];
      if (sided && onStart[v + 1] - onStart[v] > 1) {
        if (anchor < 0) {
          for (int k = 0; k < 3; ++k)
            for (int i = 0; i < 3; ++i) centroid[i] += output.positions[3 * size_t(tv[k]) + i] / 3.0;
          anchor = dist.closest(centroid, on[onStart[v]].face).primitive;
        }
        const OnFace* reached = nullptr;
        ++walk;
        queue.assign(1, uint32_t(anchor));
        seen[size_t(anchor)] = walk;
        for (size_t q = 0; q < queue.size() && q < kMaxWalk && !reached; ++q) {
          const uint32_t f = queue[q];
          for (uint32_t i = onStart[v]; i < onStart[v + 1] && !reached; ++i)
            if (on[i].face == f) reached = &on[i];
          for (int k = 0; k < 3; ++k) {
            const uint32_t g = across[3 * size_t(f) + k];
            if (g != kNone && seen[g] != walk) seen[g] = walk, queue.push_back(g);
          }
        }
        if (reached) best = reached;
        else {  // not reached: the candidate closest to the centroid
          double bestD2 = INFINITY;
          for (uint32_t i = onStart[v]; i < onStart[v + 1]; ++i) {
            const double d2 = dist.faceDistanceSquared(on[i].face, centroid);
            if (d2 < bestD2) bestD2 = d2, best = &on[i];
          }
        }
      }
      cp.face[3 * t + c] = best->face;
      std::copy(best->bary, best->bary + 3, &cp.barycentric[9 * t + 3 * c]);
    }
  }
  return cp;
}

void interpolateAttributes(const MeshBuffers& input, const CornerPoints& points, MeshBuffers& output) {
  const size_t nv = output.vertexCount(), nt = output.triangleCount();
  // the first corner of every output vertex
  std::vector<uint32_t> firstCorner(nv, kNone);
  for (size_t c = output.triangles.size(); c-- > 0;) firstCorner[output.triangles[c]] = uint32_t(c);
  auto carry = [&](const MeshAttribute& a) {
    MeshAttribute o{a.name, a.components, a.perCorner, std::vector<double>(a.itemCount(nv, nt) * a.components, 0.0)};
    for (size_t item = 0; item < a.itemCount(nv, nt); ++item) {
      const uint32_t c = a.perCorner ? uint32_t(item) : firstCorner[item];
      if (c == kNone) continue;
      interpolateAttribute(input, a, points.face[c], &points.barycentric[3 * size_t(c)], &o.values[item * a.components]);
    }
    return o;
  };
  output.attributes.clear();
  for (const MeshAttribute& a : input.attributes) output.attributes.push_back(carry(a));
  output.uvs.clear();
  if (!input.uvs.empty()) output.uvs = carry(MeshAttribute{"uv", 2, false, input.uvs}).values;
}

}  // namespace conformesh
