#include "remesh/repair.h"
#include "core/constants.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/detmath.h"
#include "core/triangle_corner.h"
#include "core/vertex_stars.h"
#include "quality/aabb_tree.h"
#include "quality/metrics.h"
#include "remesh/optimize.h"

namespace conformesh::repair {
namespace {


// A moved star triangle may turn by at most this against its own normal before the move: the
// repair straightens a corner, it does not fold the surface.
constexpr double kMaxNormalTurnDeg = 30.0;
// Candidate steps, in the star's shortest edge at the vertex, in 8 tangent directions.
constexpr double kSteps[] = {0.25, 0.1};
// A star may get as far from the input as it was, or this fraction of its shortest edge at the
// vertex, or the caller's deviationFloor (a corner of a few micro-triangles in a needle fan,
// 1e-6 of the diagonal across: 5 % of such an edge is far below any distance that shows).
constexpr double kDeviationSlack = 0.05;
// Neighbours of a triangle below the bound make room for it by moving where their own angles
// under this come closer to it (a squared deficit).
constexpr double kRoomDeg = 40.0;

class Repairer {
 public:
  Repairer(MeshBuffers& out, std::vector<uint32_t>& vertexFace, const std::vector<uint32_t>& triPatch,
           const std::vector<uint8_t>& pinned, const MeshBuffers& surface, const std::vector<uint32_t>& surfacePatch,
           double boundDeg, double deviationFloor)
      : bound_(boundDeg), deviationFloor_(deviationFloor), out_(out), vertexFace_(vertexFace), triPatch_(triPatch), pinned_(pinned), surface_(surface),
        surfacePatch_(surfacePatch), dist_(surface) {
    vertexStars(out.triangles, out.vertexCount(), start_, star_);
  }

  //! Move v to a better place on the surface; true when it moved. Strict: the star's smallest
  //! angle must rise. Room (a neighbour of a triangle below the bound): the star's deficit below
  //! kRoomDeg must fall while its smallest angle stays at or above min(its own, the bound).
  bool improve(uint32_t v, bool room = false, bool relaxed = false) {
    if (v >= pinned_.size() || pinned_[v]) return false;
    const uint32_t* s = &star_[start_[v]];
    const size_t n = start_[v + 1] - start_[v];
    if (n == 0) return false;
    const Vec3 p0 = vec3At(out_.positions, v);
    std::vector<Vec3> normal0(n);
    double min0 = 180, shortest = INFINITY, dev0 = 0, deficit0 = 0;
    size_t below0 = 0;
    Vec3 ring{0, 0, 0}, apex{0, 0, 0}, nsum{0, 0, 0};
    for (size_t i = 0; i < n; ++i) {
      const auto [a, b] = rim(s[i], v);
      const double m0 = optimization::minAngleDeg3(p0, a, b);
      min0 = std::min(min0, m0);
      below0 += m0 < bound_;
      deficit0 += m0 < kRoomDeg ? (kRoomDeg - m0) * (kRoomDeg - m0) : 0.0;
      normal0[i] = cross(a - p0, b - p0);
      nsum = nsum + normal0[i];
      shortest = std::min({shortest, norm(a - p0), norm(b - p0)});
      ring = ring + (a + b) * 0.5;
      // the apex of the equilateral triangle on ab, on v's side in the triangle's plane
      const Vec3 mid = (a + b) * 0.5, ab = b - a;
      const Vec3 side = cross(normal0[i], ab);  // in the plane, perpendicular to ab, toward v
      const double ls = norm(side);
      if (ls > 0) apex = apex + mid + side * (0.86602540378443864676 * norm(ab) / ls);
      else apex = apex + mid;
      dev0 = std::max(dev0, deviation(p0, a, b));
    }
    if (!(shortest > 0) || !std::isfinite(shortest)) return false;
    const double ln = norm(nsum);
    if (!(ln > 0)) return false;
    const Vec3 nrm = nsum * (1.0 / ln);
    // tangent basis
    Vec3 e1 = std::abs(nrm.x) < 0.9 ? cross(nrm, Vec3{1, 0, 0}) : cross(nrm, Vec3{0, 1, 0});
    e1 = e1 * (1.0 / norm(e1));
    const Vec3 e2 = cross(nrm, e1);
    std::vector<Vec3> cand;
    cand.push_back(apex * (1.0 / double(n)));
    cand.push_back(ring * (1.0 / double(n)));
    for (double step : kSteps)
      for (int d = 0; d < 8; ++d) {
        const double a = d * 0.78539816339744830962;
        cand.push_back(p0 + e1 * (step * shortest * dmath::cos(a)) + e2 * (step * shortest * dmath::sin(a)));
      }
    const double cosTurn = dmath::cos(kMaxNormalTurnDeg * kPi / 180.0);
    const double devLimit = std::max({dev0, kDeviationSlack * shortest, deviationFloor_});
    double best = room ? deficit0 - 1e-9 : min0 + 1e-9;
    const double floor = std::min(min0, bound_);
    Vec3 bestP{};
    int64_t bestFace = -1;
    for (const Vec3& c : cand) {
      const quality::ClosestHit h = dist_.closest(c, vertexFace_[v]);
      if (h.primitive < 0) continue;
      const uint32_t f = uint32_t(h.primitive);
      bool inStar = false;
      for (size_t i = 0; i < n && !inStar; ++i) inStar = triPatch_[s[i]] == surfacePatch_[f];
      if (!inStar) continue;  // across a feature (or into a patch the star does not touch)
      const uint32_t* fv = &surface_.triangles[3 * size_t(f)];
      const Vec3 p = quality::closestPointOnTriangle(c, vec3At(surface_.positions, fv[0]), vec3At(surface_.positions, fv[1]), vec3At(surface_.positions, fv[2]));
      double mn = 180, deficit = 0;
      size_t below = 0;
      bool ok = true;
      for (size_t i = 0; i < n && ok; ++i) {
        const auto [a, b] = rim(s[i], v);
        const double m = optimization::minAngleDeg3(p, a, b);
        mn = std::min(mn, m);
        below += m < bound_;
        deficit += m < kRoomDeg ? (kRoomDeg - m) * (kRoomDeg - m) : 0.0;
        if ((room ? !(mn >= floor) : !(mn > best)) || below > below0 + (relaxed ? 1 : 0)) ok = false;
        const Vec3 nn = cross(a - p, b - p);
        if (!(dot(nn, normal0[i]) > cosTurn * norm(nn) * norm(normal0[i]))) ok = false;
      }
      if (!ok || (room && !(deficit < best))) continue;
      double dev = 0;
      for (size_t i = 0; i < n && dev <= devLimit; ++i) {
        const auto [a, b] = rim(s[i], v);
        dev = std::max(dev, deviation(p, a, b));
      }
      if (!(dev <= devLimit)) continue;
      best = room ? deficit : mn;
      bestP = p;
      bestFace = h.primitive;
    }
    if (bestFace < 0) return false;
    double* q = &out_.positions[3 * size_t(v)];
    q[0] = bestP.x, q[1] = bestP.y, q[2] = bestP.z;
    vertexFace_[v] = uint32_t(bestFace);
    return true;
  }

  //! Append the triangles of v's star.
  void starTriangles(uint32_t v, std::vector<size_t>& out) const {
    for (uint32_t k = start_[v]; k < start_[v + 1]; ++k) out.push_back(star_[k]);
  }

  //! Append the vertices of v's star (v included).
  void neighbours(uint32_t v, std::vector<uint32_t>& out) const {
    for (uint32_t k = start_[v]; k < start_[v + 1]; ++k)
      for (int c = 0; c < 3; ++c) out.push_back(out_.triangles[3 * size_t(star_[k]) + c]);
  }

 private:
  // The two other corners of output triangle t, in order after v.
  std::pair<Vec3, Vec3> rim(uint32_t t, uint32_t v) const {
    const uint32_t* c = &out_.triangles[3 * size_t(t)];
    const int k = cornerOf(c, v);
    return {vec3At(out_.positions, c[(k + 1) % 3]), vec3At(out_.positions, c[(k + 2) % 3])};
  }
  // Largest distance to the input from the centroid of triangle (p, a, b) and the midpoints of
  // its two edges at p (the third edge does not move).
  double deviation(const Vec3& p, const Vec3& a, const Vec3& b) const {
    const Vec3 pts[3] = {(p + a + b) * (1.0 / 3.0), (p + a) * 0.5, (p + b) * 0.5};
    double d = 0;
    for (const Vec3& x : pts) d = std::max(d, dist_.closest(x).distanceSquared);
    return std::sqrt(d);
  }

  double bound_, deviationFloor_;
  MeshBuffers& out_;
  std::vector<uint32_t>& vertexFace_;
  const std::vector<uint32_t>& triPatch_;
  const std::vector<uint8_t>& pinned_;
  const MeshBuffers& surface_;
  const std::vector<uint32_t>& surfacePatch_;
  quality::TriangleMeshDistance dist_;
  std::vector<uint32_t> start_, star_;
};

}  // namespace

RepairStats relaxBelowBound(MeshBuffers& out, std::vector<uint32_t>& vertexFace, const std::vector<uint32_t>& triPatch,
                            const std::vector<uint8_t>& pinned, const MeshBuffers& surface,
                            const std::vector<uint32_t>& surfacePatch, const std::function<bool(size_t)>& isBad,
                            double boundDeg, int maxRounds, double deviationFloor) {
  RepairStats st;
  std::vector<size_t> bad;
  for (size_t t = 0; t < out.triangleCount(); ++t)
    if (isBad(t)) bad.push_back(t);
  if (bad.empty()) return st;
  Repairer r(out, vertexFace, triPatch, pinned, surface, surfacePatch, boundDeg, deviationFloor);
  // the relaxed moves may leave more triangles below the bound than there were: then the
  // positions as they came are restored
  const size_t badBefore = bad.size();
  const std::vector<double> positionsBefore = out.positions;
  const std::vector<uint32_t> facesBefore = vertexFace;
  // every triangle that was below the bound or in the star of a moved vertex: a move can push a
  // star triangle below the bound while it lifts another, so the triangles below the bound are
  // always among these
  std::vector<size_t> all = bad;
  auto tryImprove = [&](uint32_t v, bool room, bool relaxed) {
    if (!r.improve(v, room, relaxed)) return false;
    r.starTriangles(v, all);
    return true;
  };
  for (; st.rounds < maxRounds && !bad.empty(); ++st.rounds) {
    size_t moved = 0;
    for (size_t t : bad)
      for (int c = 0; c < 3; ++c)
        if (isBad(t) && tryImprove(out.triangles[3 * t + c], false, false)) ++moved;
    if (moved == 0) {
      // nothing of the triangles themselves moves: their free neighbours make room
      std::vector<uint32_t> ring;
      for (size_t t : bad)
        for (int c = 0; c < 3; ++c) r.neighbours(out.triangles[3 * t + c], ring);
      std::sort(ring.begin(), ring.end());
      ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
      for (uint32_t v : ring)
        if (tryImprove(v, true, false)) ++moved;
    }
    if (moved == 0) {
      // nor do the neighbours: a vertex of a triangle below the bound may raise its star's
      // smallest angle at the price of one more star triangle below the bound (two near-bound
      // triangles that the next passes can lift)
      for (size_t t : bad)
        for (int c = 0; c < 3; ++c)
          if (isBad(t) && tryImprove(out.triangles[3 * t + c], false, true)) ++moved;
    }
    st.moves += moved;
    if (moved == 0) break;
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    std::vector<size_t> still;
    for (size_t t : all)
      if (isBad(t)) still.push_back(t);
    bad.swap(still);
  }
  st.left = bad.size();
  if (st.left > badBefore) {  // undone: no move stands
    out.positions = positionsBefore;
    vertexFace = facesBefore;
    st.left = badBefore;
    st.moves = 0;
  }
  return st;
}

}  // namespace conformesh::repair
