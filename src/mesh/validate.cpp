#include "mesh/validate.h"

#include <algorithm>
#include <string>
#include <utility>

#include "mesh/edge_groups.h"
#include "mesh/mesh_checks.h"

namespace conformesh {

namespace {
std::string tri(const std::vector<uint32_t>& t, const std::vector<uint32_t>& faceToInput, uint32_t f) {
  return "triangle " + std::to_string(faceToInput[f]) + " (" + std::to_string(t[3 * f]) + " " +
         std::to_string(t[3 * f + 1]) + " " + std::to_string(t[3 * f + 2]) + ")";
}

// Keep the triangles whose flag is 0.
void dropFaces(std::vector<uint32_t>& tris, std::vector<uint32_t>& faceToInput, const std::vector<uint8_t>& drop) {
  size_t k = 0;
  for (size_t f = 0; f < faceToInput.size(); ++f) {
    if (drop[f]) continue;
    for (int i = 0; i < 3; ++i) tris[3 * k + i] = tris[3 * f + i];
    faceToInput[k++] = faceToInput[f];
  }
  tris.resize(3 * k);
  faceToInput.resize(k);
}
}  // namespace

ValidatedMesh validate(const MeshBuffers& input, const ValidateOptions& options) {
  using detail::kNone;
  const Stage S = Stage::Validate;
  detail::checkBuffers(input, options.maxVertices, options.maxTriangles, S);
  const size_t nvIn = input.vertexCount();

  ValidatedMesh out;
  ValidationReport& rep = out.report;
  rep.inputVertices = nvIn;
  rep.inputTriangles = input.triangleCount();

  // Degenerate triangles.
  detail::FaceFilter ff = detail::filterDegenerateFaces(input, options.dropZeroAreaFaces);
  std::vector<uint32_t> tris = std::move(ff.tris);
  std::vector<uint32_t> faceToInput = std::move(ff.faceToInput);
  rep.zeroAreaFaces = ff.zeroArea;
  rep.degenerateFaces = ff.repeatedVertex + (options.dropZeroAreaFaces ? ff.zeroArea : 0);
  if (rep.degenerateFaces > 0)
    rep.warnings.push_back({Code::DegenerateFace, rep.degenerateFaces,
                            "dropped " + std::to_string(rep.degenerateFaces) + " degenerate triangles (" +
                                std::to_string(ff.repeatedVertex) + " with a repeated vertex, " +
                                std::to_string(rep.degenerateFaces - ff.repeatedVertex) +
                                " with zero area), e.g. triangle " + std::to_string(ff.firstDegenerate)});
  if (!options.dropZeroAreaFaces && ff.zeroArea > 0)
    rep.warnings.push_back({Code::DegenerateFace, ff.zeroArea,
                            "kept " + std::to_string(ff.zeroArea) + " zero-area triangles"});

  // Duplicate triangles.
  {
    detail::Duplicates d = detail::findDuplicateFaces(tris);
    if (d.count > 0) {
      if (!options.dropDuplicateFaces)
        fail(Code::NonManifoldEdge, S,
             tri(tris, faceToInput, d.first) + " uses the same vertices as " + tri(tris, faceToInput, d.firstOriginal) +
                 " (" + std::to_string(d.count) + " duplicate triangles)");
      dropFaces(tris, faceToInput, d.isDuplicate);
      rep.duplicateFaces = d.count;
      rep.warnings.push_back({Code::DegenerateFace, d.count,
                              "dropped " + std::to_string(d.count) + " duplicate triangles"});
    }
  }
  if (tris.empty())
    fail(Code::EmptyMesh, S, "every one of the " + std::to_string(rep.inputTriangles) + " triangles is degenerate");

  // Non-manifold edges.
  detail::EdgeGroups groups = detail::groupEdges(nvIn, tris);
  detail::EdgeStats es = detail::edgeStats(groups, tris);
  if (es.nonManifoldEdges > 0) {
    uint32_t c = es.firstNonManifoldCorner;
    uint32_t a = tris[c], b = detail::cornerTip(tris, c);
    fail(Code::NonManifoldEdge, S,
         "edge (" + std::to_string(std::min(a, b)) + ", " + std::to_string(std::max(a, b)) + ") is shared by " +
             std::to_string(es.firstNonManifoldFaces) + " triangles, e.g. " + tri(tris, faceToInput, c / 3) + " (" +
             std::to_string(es.nonManifoldEdges) + " non-manifold edges)");
  }

  // Orientation.
  detail::Orientation o = detail::orientFaces(tris, es.partner);
  if (o.nonOrientableComponents > 0)
    fail(Code::InvalidTopology, S,
         "the connected part containing " + tri(tris, faceToInput, o.firstNonOrientableFace) +
             " is not orientable (a Möbius strip or Klein bottle): it has no consistent orientation");
  // Fans, computed before the flips (they do not depend on orientation).
  detail::Fans fans = detail::vertexFans(nvIn, tris, es.partner);
  es = detail::EdgeStats();
  if (o.flipped > 0) {
    if (!options.fixOrientation)
      fail(Code::InconsistentOrientation, S,
           std::to_string(o.inconsistentEdges) + " edges are traversed the same way by both triangles; " +
               std::to_string(o.flipped) + " triangles would need reversing");
    for (size_t f = 0; f < o.flip.size(); ++f) {
      if (!o.flip[f]) continue;
      std::swap(tris[3 * f + 1], tris[3 * f + 2]);
      std::swap(fans.cornerFan[3 * f + 1], fans.cornerFan[3 * f + 2]);
    }
    // Reversing (v0 v1 v2) into (v0 v2 v1) moves the edge of corner i to corner 2 - i.
    for (uint32_t& c : groups.corners)
      if (o.flip[c / 3]) c = c - c % 3 + (2 - c % 3);
    rep.flippedFaces = o.flipped;
    rep.warnings.push_back({Code::InconsistentOrientation, o.flipped,
                            "reversed " + std::to_string(o.flipped) +
                                " triangles to make the orientation consistent (majority kept per component)"});
  }

  // Bow-tie vertices: each fan beyond a vertex's first gets a new vertex (copy of the original).
  std::vector<uint32_t> splitOrigin;  // new vertex nvIn + k copies input vertex splitOrigin[k]
  if (fans.bowtieVertices > 0) {
    if (!options.splitNonManifoldVertices)
      fail(Code::NonManifoldVertex, S,
           "vertex " + std::to_string(fans.firstBowtie) + " joins separate fans of triangles (bow-tie; " +
               std::to_string(fans.bowtieVertices) + " such vertices)");
    std::vector<uint32_t> fanVertex(tris.size(), kNone);  // indexed by representative corner
    std::vector<uint8_t> claimed(nvIn, 0);
    for (size_t c = 0; c < tris.size(); ++c) {
      uint32_t r = fans.cornerFan[c];
      if (fanVertex[r] == kNone) {
        uint32_t v = tris[c];
        if (!claimed[v]) {
          claimed[v] = 1;
          fanVertex[r] = v;
        } else {
          fanVertex[r] = uint32_t(nvIn + splitOrigin.size());
          splitOrigin.push_back(v);
        }
      }
      tris[c] = fanVertex[r];
    }
    rep.splitVertices = splitOrigin.size();
    rep.warnings.push_back({Code::NonManifoldVertex, fans.bowtieVertices,
                            "split " + std::to_string(fans.bowtieVertices) + " bow-tie vertices into " +
                                std::to_string(fans.bowtieVertices + splitOrigin.size()) + " manifold vertices"});
  }
  fans = detail::Fans();

  // Remove unreferenced vertices; copies of split vertices follow the kept ones.
  const size_t nvAll = nvIn + splitOrigin.size();
  std::vector<uint32_t> newIndex(nvAll, kNone);
  for (uint32_t v : tris) newIndex[v] = 0;
  out.vertexToInput.clear();
  for (size_t v = 0; v < nvAll; ++v) {
    if (newIndex[v] == kNone) continue;
    newIndex[v] = uint32_t(out.vertexToInput.size());
    out.vertexToInput.push_back(v < nvIn ? uint32_t(v) : splitOrigin[v - nvIn]);
  }
  const size_t nvOut = out.vertexToInput.size();
  size_t usedInput = 0;
  for (size_t v = 0; v < nvIn; ++v) usedInput += newIndex[v] != kNone ? 1 : 0;
  rep.removedVertices = nvIn - usedInput;
  if (rep.removedVertices > 0)
    rep.warnings.push_back({Code::Ok, rep.removedVertices,
                            "removed " + std::to_string(rep.removedVertices) + " vertices that no triangle uses"});
  out.inputToVertex.assign(nvIn, kNone);
  for (size_t v = 0; v < nvOut; ++v)
    if (out.inputToVertex[out.vertexToInput[v]] == kNone) out.inputToVertex[out.vertexToInput[v]] = uint32_t(v);
  for (uint32_t& v : tris) v = newIndex[v];

  MeshBuffers& b = out.buffers;
  b.positions.resize(3 * nvOut);
  for (size_t v = 0; v < nvOut; ++v)
    for (int k = 0; k < 3; ++k) b.positions[3 * v + k] = input.positions[3 * size_t(out.vertexToInput[v]) + k];
  if (!input.uvs.empty()) {
    b.uvs.resize(2 * nvOut);
    for (size_t v = 0; v < nvOut; ++v)
      for (int k = 0; k < 2; ++k) b.uvs[2 * v + k] = input.uvs[2 * size_t(out.vertexToInput[v]) + k];
  }
  b.triangles = std::move(tris);
  out.faceToInput = std::move(faceToInput);
  // Splitting and renumbering vertices keeps each edge's corners together: the groups still hold.
  out.mesh = HalfedgeMesh::fromGroupedTriangles(nvOut, b.triangles, std::move(groups));
  out.positions = vertexPositions(b);
  return out;
}

}  // namespace conformesh
