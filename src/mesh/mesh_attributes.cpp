// conformesh — mesh attributes: checks, seams (edges sorted by their vertex pair), interpolation.
#include "mesh/mesh_attributes.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "mesh/mesh_checks.h"

namespace conformesh {

void checkAttributes(const MeshBuffers& mesh, Stage stage) {
  const size_t nv = mesh.vertexCount(), nt = mesh.triangleCount();
  if (!mesh.uvs.empty() && mesh.uvs.size() != 2 * nv)
    fail(Code::InvalidArgument, stage, "uvs must be empty or hold 2 values per vertex");
  if (!mesh.attributes.empty() && mesh.triangles.size() % 3 != 0)
    fail(Code::InvalidArgument, stage, "triangles size is not a multiple of 3");
  if (!mesh.attributes.empty())
    for (uint32_t t : mesh.triangles)
      if (t >= nv) fail(Code::IndexOutOfRange, stage, "triangle index " + std::to_string(t) + " >= vertex count");
  for (const MeshAttribute& a : mesh.attributes) {
    if (a.name.empty()) fail(Code::InvalidArgument, stage, "an attribute has no name");
    if (a.components == 0) fail(Code::InvalidArgument, stage, "attribute '" + a.name + "' has 0 components");
    const size_t want = a.itemCount(nv, nt) * a.components;
    if (a.values.size() != want)
      fail(Code::InvalidArgument, stage,
           "attribute '" + a.name + "' has " + std::to_string(a.values.size()) + " values; expected " +
               std::to_string(want) + (a.perCorner ? " (per triangle corner)" : " (per vertex)"));
    for (size_t i = 0; i < a.values.size(); ++i)
      if (!std::isfinite(a.values[i]))
        fail(Code::NonFiniteCoordinate, stage, "attribute '" + a.name + "' value " + std::to_string(i) + " is not finite");
  }
}

namespace {

// One triangle side: the vertex pair (smaller first), its triangle and the corner it starts at.
struct Side {
  uint32_t a, b, t, corner;
  bool operator<(const Side& o) const { return a != o.a ? a < o.a : b != o.b ? b < o.b : t < o.t; }
};

// The corner of triangle t at vertex v (3 when v is not one of its vertices).
uint32_t cornerAt(const MeshBuffers& m, uint32_t t, uint32_t v) {
  uint32_t c = 0;
  while (c < 3 && m.triangles[3 * size_t(t) + c] != v) ++c;
  return c;
}

bool sameCornerValues(const MeshBuffers& m, size_t c0, size_t c1) {
  for (const MeshAttribute& a : m.attributes) {
    if (!a.perCorner) continue;
    const double* x = &a.values[c0 * a.components];
    const double* y = &a.values[c1 * a.components];
    if (!std::equal(x, x + a.components, y)) return false;
  }
  return true;
}

// Visit every edge with exactly two triangles: f(side0, side1, isSeam).
template <class F>
void forEachInteriorEdge(const MeshBuffers& m, F&& f) {
  std::vector<Side> sides;
  sides.reserve(m.triangles.size());
  // the triangles validation keeps (no repeated vertex, not exactly collinear)
  for (uint32_t t : detail::filterDegenerateFaces(m, true).faceToInput) {
    const uint32_t* v = &m.triangles[3 * size_t(t)];
    for (uint32_t c = 0; c < 3; ++c) {
      const uint32_t p = v[c], q = v[(c + 1) % 3];
      sides.push_back({std::min(p, q), std::max(p, q), t, c});
    }
  }
  std::sort(sides.begin(), sides.end());
  for (size_t i = 0; i < sides.size();) {
    size_t j = i + 1;
    while (j < sides.size() && sides[j].a == sides[i].a && sides[j].b == sides[i].b) ++j;
    if (j == i + 2) {
      const Side &s0 = sides[i], &s1 = sides[i + 1];
      bool seam = false;
      for (uint32_t v : {s0.a, s0.b})
        seam |= !sameCornerValues(m, 3 * size_t(s0.t) + cornerAt(m, s0.t, v), 3 * size_t(s1.t) + cornerAt(m, s1.t, v));
      f(s0, s1, seam);
    }
    i = j;
  }
}

bool hasPerCorner(const MeshBuffers& m) {
  return std::any_of(m.attributes.begin(), m.attributes.end(), [](const MeshAttribute& a) { return a.perCorner; });
}

}  // namespace

std::vector<std::array<uint32_t, 2>> attributeSeams(const MeshBuffers& mesh) {
  std::vector<std::array<uint32_t, 2>> seams;
  if (!hasPerCorner(mesh)) return seams;
  forEachInteriorEdge(mesh, [&](const Side& s0, const Side&, bool seam) {
    if (seam) seams.push_back({s0.a, s0.b});
  });
  return seams;
}

std::vector<uint32_t> neighboursWithinCharts(const MeshBuffers& mesh) {
  std::vector<uint32_t> across(mesh.triangles.size(), UINT32_MAX);
  forEachInteriorEdge(mesh, [&](const Side& s0, const Side& s1, bool seam) {
    if (seam) return;
    across[3 * size_t(s0.t) + s0.corner] = s1.t;
    across[3 * size_t(s1.t) + s1.corner] = s0.t;
  });
  return across;
}

void interpolateAttribute(const MeshBuffers& mesh, const MeshAttribute& a, uint32_t t, const double bary[3], double* out) {
  const uint32_t k = a.components;
  std::fill(out, out + k, 0.0);
  for (int c = 0; c < 3; ++c) {
    const size_t item = a.perCorner ? 3 * size_t(t) + size_t(c) : size_t(mesh.triangles[3 * size_t(t) + size_t(c)]);
    for (uint32_t i = 0; i < k; ++i) out[i] += bary[c] * a.values[item * k + i];
  }
  if (a.name == "normal" && k == 3) {
    const double len = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
    if (len > 0)
      for (uint32_t i = 0; i < 3; ++i) out[i] /= len;
  }
}

}  // namespace conformesh
