#include "mesh/precondition.h"
#include "core/constants.h"
#include "core/detmath.h"
#include "core/vec3.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

namespace conformesh {
namespace {

constexpr uint32_t kNo = 0xffffffffu;

uint64_t edgeKey(uint32_t a, uint32_t b) { return a < b ? (uint64_t(a) << 32 | b) : (uint64_t(b) << 32 | a); }


class Editor {
 public:
  Editor(const MeshBuffers& m, const std::vector<std::array<uint32_t, 2>>& prot, const std::vector<uint8_t>& mask)
      : P_(m.positions) {
    const size_t nf = m.triangleCount();
    T_.resize(nf);
    for (size_t f = 0; f < nf; ++f) {
      T_[f] = {m.triangles[3 * f], m.triangles[3 * f + 1], m.triangles[3 * f + 2]};
      addFace(uint32_t(f));
    }
    origin_.resize(nf);
    for (uint32_t f = 0; f < nf; ++f) origin_[f] = f;
    mask_.assign(nf, 1);
    if (mask.size() == nf) mask_ = mask;
    parents_.resize(m.vertexCount());
    for (uint32_t v = 0; v < parents_.size(); ++v) parents_[v] = {v, v};
    for (const auto& e : prot)
      if (ef_.count(edgeKey(e[0], e[1]))) prot_.insert(edgeKey(e[0], e[1]));
  }

  Vec3 pos(uint32_t v) const { return vec3At(P_, v); }
  double edgeLength(uint32_t a, uint32_t b) const { return norm(pos(a) - pos(b)); }

  // Split every edge longer than maxLen at its midpoint, longest first.
  void splitLong(double maxLen, size_t maxNew, Preconditioned& out) {
    using Item = std::tuple<double, uint32_t, uint32_t>;
    std::priority_queue<Item> q;
    for (const auto& [k, fs] : ef_) {
      (void)fs;
      uint32_t a = uint32_t(k >> 32), b = uint32_t(k & 0xffffffffu);
      double l = edgeLength(a, b);
      if (l > maxLen && editable(k)) q.push({l, a, b});
    }
    size_t added = 0;
    while (!q.empty()) {
      auto [l, a, b] = q.top();
      q.pop();
      if (!ef_.count(edgeKey(a, b))) continue;  // already split
      if (added >= maxNew) {
        out.capped = true;
        break;
      }
      uint32_t m = splitEdge(a, b);
      ++added;
      ++out.splits;
      for (uint32_t x : lastNeighbours_) {
        double lx = edgeLength(m, x);
        if (lx > maxLen && editable(edgeKey(m, x))) q.push({lx, m, x});
      }
    }
  }

  // Lawson flips of coplanar interior edges toward the Delaunay triangulation of each plane.
  void flipCoplanar(double tol, Preconditioned& out) {
    std::vector<uint64_t> work;
    work.reserve(ef_.size());
    for (const auto& kv : ef_) work.push_back(kv.first);
    std::sort(work.begin(), work.end());  // a fixed order: the result does not depend on hashing
    const size_t cap = 50 * ef_.size() + 1000;
    for (size_t step = 0; step < cap && !work.empty(); ++step) {
      uint64_t k = work.back();
      work.pop_back();
      uint32_t c, d, a, b;
      std::array<uint32_t, 2> fs;
      if (!flippable(k, tol, a, b, c, d, fs)) continue;
      removeFace(fs[0]);
      removeFace(fs[1]);
      T_[fs[0]] = {a, d, c};
      T_[fs[1]] = {d, b, c};
      addFace(fs[0]);
      addFace(fs[1]);
      ++out.flips;
      for (auto e : {edgeKey(a, d), edgeKey(d, b), edgeKey(b, c), edgeKey(c, a)}) work.push_back(e);
    }
  }

  void write(Preconditioned& out) const {
    out.mesh.positions = P_;
    out.mesh.triangles.clear();
    out.mesh.triangles.reserve(3 * T_.size());
    for (const auto& t : T_) out.mesh.triangles.insert(out.mesh.triangles.end(), t.begin(), t.end());
    out.parents = parents_;
    out.faceOrigin = origin_;
    std::vector<uint64_t> keys(prot_.begin(), prot_.end());
    std::sort(keys.begin(), keys.end());
    for (uint64_t k : keys) out.protectedEdges.push_back({uint32_t(k >> 32), uint32_t(k & 0xffffffffu)});
  }

 private:
  void addFace(uint32_t f) {
    for (int c = 0; c < 3; ++c) {
      auto it = ef_.try_emplace(edgeKey(T_[f][c], T_[f][(c + 1) % 3]), std::array<uint32_t, 2>{kNo, kNo}).first;
      (it->second[0] == kNo ? it->second[0] : it->second[1]) = f;
    }
  }
  void removeFace(uint32_t f) {
    for (int c = 0; c < 3; ++c) {
      auto it = ef_.find(edgeKey(T_[f][c], T_[f][(c + 1) % 3]));
      if (it == ef_.end()) continue;
      auto& s = it->second;
      if (s[0] == f) s = {s[1], kNo};
      else if (s[1] == f) s[1] = kNo;
      if (s[0] == kNo) ef_.erase(it);
    }
  }
  uint32_t splitEdge(uint32_t a, uint32_t b) {
    const std::array<uint32_t, 2> fs = ef_.at(edgeKey(a, b));
    const uint32_t m = uint32_t(P_.size() / 3);
    const Vec3 pa = pos(a), pb = pos(b);
    P_.insert(P_.end(), {0.5 * (pa.x + pb.x), 0.5 * (pa.y + pb.y), 0.5 * (pa.z + pb.z)});
    parents_.push_back({a, b});
    if (prot_.erase(edgeKey(a, b))) {
      prot_.insert(edgeKey(a, m));
      prot_.insert(edgeKey(m, b));
    }
    lastNeighbours_ = {a, b};
    for (uint32_t f : fs) {
      if (f == kNo) continue;
      int c = 0;
      while (!((T_[f][c] == a && T_[f][(c + 1) % 3] == b) || (T_[f][c] == b && T_[f][(c + 1) % 3] == a))) ++c;
      const uint32_t x = T_[f][c], y = T_[f][(c + 1) % 3], z = T_[f][(c + 2) % 3];
      removeFace(f);
      T_[f] = {x, m, z};
      addFace(f);
      T_.push_back({m, y, z});
      origin_.push_back(origin_[f]);
      mask_.push_back(mask_[f]);
      addFace(uint32_t(T_.size() - 1));
      lastNeighbours_.push_back(z);
    }
    return m;
  }

  // The edge k and its two triangles (a, b, c) and (b, a, d), when it is interior, not protected,
  // its triangles are coplanar, it is not locally Delaunay and the flip keeps both orientations.
  bool flippable(uint64_t k, double tol, uint32_t& a, uint32_t& b, uint32_t& c, uint32_t& d,
                 std::array<uint32_t, 2>& fs) const {
    auto it = ef_.find(k);
    if (it == ef_.end() || it->second[1] == kNo || prot_.count(k) || !editable(k)) return false;
    fs = it->second;
    const uint32_t u = uint32_t(k >> 32), v = uint32_t(k & 0xffffffffu);
    int i = 0;
    while (!((T_[fs[0]][i] == u || T_[fs[0]][i] == v) && (T_[fs[0]][(i + 1) % 3] == u || T_[fs[0]][(i + 1) % 3] == v))) ++i;
    a = T_[fs[0]][i];
    b = T_[fs[0]][(i + 1) % 3];
    c = T_[fs[0]][(i + 2) % 3];
    d = kNo;
    for (uint32_t x : T_[fs[1]])
      if (x != a && x != b) d = x;
    if (d == kNo || c == d || ef_.count(edgeKey(c, d))) return false;
    const Vec3 pa = pos(a), pb = pos(b), pc = pos(c), pd = pos(d);
    const Vec3 n0 = cross(pb - pa, pc - pa), n1 = cross(pa - pb, pd - pb);
    const double l0 = norm(n0), l1 = norm(n1);
    if (!(l0 > 0 && l1 > 0) || 1.0 - dot(n0, n1) / (l0 * l1) > tol) return false;
    auto angle = [](const Vec3& p, const Vec3& q, const Vec3& r) {  // at p
      const Vec3 x = q - p, y = r - p;
      return dmath::atan2(norm(cross(x, y)), dot(x, y));
    };
    if (angle(pc, pa, pb) + angle(pd, pb, pa) <= kPi * (1 + 1e-12)) return false;
    // both new triangles keep the orientation (the quad is strictly convex at a and b)
    const Vec3 m0 = cross(pd - pa, pc - pa), m1 = cross(pb - pd, pc - pd);
    const double eps = 1e-12 * l0;
    return dot(m0, n0) > eps * l0 && dot(m1, n0) > eps * l0;
  }

  std::vector<double> P_;
  std::vector<std::array<uint32_t, 3>> T_;
  std::unordered_map<uint64_t, std::array<uint32_t, 2>> ef_;
  std::unordered_set<uint64_t> prot_;
  std::vector<std::array<uint32_t, 2>> parents_;
  std::vector<uint32_t> origin_;  // per triangle: the input triangle it lies in
  std::vector<uint8_t> mask_;     // per triangle: may be changed

  bool editable(uint64_t k) const {
    auto it = ef_.find(k);
    if (it == ef_.end()) return false;
    for (uint32_t f : it->second)
      if (f != kNo && mask_[f]) return true;
    return false;
  }
  std::vector<uint32_t> lastNeighbours_;  // the vertices joined to the latest split vertex
};

}  // namespace

Preconditioned precondition(const MeshBuffers& input, const std::vector<std::array<uint32_t, 2>>& protectedEdges,
                            const PreconditionOptions& options) {
  Preconditioned out;
  if (options.faceMask.size() == input.triangleCount() &&
      std::none_of(options.faceMask.begin(), options.faceMask.end(), [](uint8_t m) { return m != 0; })) {
    // nothing may change: the input as it is, without building the edge map
    out.mesh = input;
    out.parents.resize(input.vertexCount());
    for (uint32_t v = 0; v < out.parents.size(); ++v) out.parents[v] = {v, v};
    out.faceOrigin.resize(input.triangleCount());
    for (uint32_t f = 0; f < out.faceOrigin.size(); ++f) out.faceOrigin[f] = f;
    // the protected pairs that are edges, as the editor keeps them (sorted keys, smaller first)
    std::unordered_set<uint64_t> wanted, found;
    for (const auto& e : protectedEdges) wanted.insert(edgeKey(e[0], e[1]));
    for (size_t t = 0; t < input.triangles.size() && !wanted.empty(); t += 3)
      for (int c = 0; c < 3; ++c) {
        const uint64_t k = edgeKey(input.triangles[t + c], input.triangles[t + (c + 1) % 3]);
        if (wanted.count(k)) found.insert(k);
      }
    std::vector<uint64_t> keys(found.begin(), found.end());
    std::sort(keys.begin(), keys.end());
    for (uint64_t k : keys) out.protectedEdges.push_back({uint32_t(k >> 32), uint32_t(k & 0xffffffffu)});
    return out;
  }
  Editor ed(input, protectedEdges, options.faceMask);
  // split, flip, and once more: the flips make shorter diagonals, the second split pass only
  // finds the long edges flipping could not remove
  for (int pass = 0; pass < 2; ++pass) {
    if (options.maxEdgeLength > 0) ed.splitLong(options.maxEdgeLength, options.maxNewVertices - std::min(options.maxNewVertices, out.splits), out);
    ed.flipCoplanar(options.coplanarTolerance, out);
  }
  ed.write(out);
  return out;
}

}  // namespace conformesh
