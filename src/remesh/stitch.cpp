#include "remesh/stitch.h"

namespace conformesh::pipeline {

MeshBuffers stitch(const Surface& surf, const Meshing& m, std::vector<uint32_t>& trianglePatch,
                   std::vector<uint32_t>& vertexFace) {
  const Patches& work = m.patches;
  const F::CurveMesh& cm = m.samples.cm;
  MeshBuffers out;
  size_t nv = cm.samples.size(), nt = 0;
  for (const auto& w : work) {
    for (uint32_t g : w->localToGlobal) nv += g == kNone;
    nt += w->triangles.size() / 3;
  }
  out.positions.reserve(3 * nv);
  out.triangles.reserve(3 * nt);
  trianglePatch.clear();
  trianglePatch.reserve(nt);
  vertexFace.assign(nv, kNone);
  auto inputFace = [&](uint32_t gf) { return gf < surf.pre.faceOrigin.size() ? surf.pre.faceOrigin[gf] : kNone; };
  for (size_t i = 0; i < cm.samples.size(); ++i) {
    const F::CurveSample& s = cm.samples[i];
    out.positions.insert(out.positions.end(), {s.position.x, s.position.y, s.position.z});
    uint32_t e = s.edge;
    if (e == kNone && s.vertex != kNone && s.vertex < surf.g.vertexCount && surf.g.vertexEdgeStart[s.vertex] < surf.g.vertexEdgeStart[s.vertex + 1])
      e = surf.g.vertexEdgeIds[surf.g.vertexEdgeStart[s.vertex]];
    if (e != kNone && e < surf.g.edgeCount()) vertexFace[i] = inputFace(surf.g.edgeFaces[e][0] != kNone ? surf.g.edgeFaces[e][0] : surf.g.edgeFaces[e][1]);
  }
  for (uint32_t p = 0; p < work.size(); ++p) {
    const PatchWork& w = *work[p];
    std::vector<uint32_t> id(w.localToGlobal.size());
    for (size_t v = 0; v < id.size(); ++v) {
      if (w.localToGlobal[v] != kNone) id[v] = w.localToGlobal[v];
      else {
        id[v] = uint32_t(out.positions.size() / 3);
        const auto& q = w.interiorPositions[v];
        out.positions.insert(out.positions.end(), {q.x, q.y, q.z});
        if (w.liftFaces[v] != kNone) vertexFace[id[v]] = inputFace(w.liftFaces[v]);
      }
    }
    for (size_t t = 0; t < w.triangles.size(); t += 3) {
      out.triangles.insert(out.triangles.end(), {id[w.triangles[t]], id[w.triangles[t + 1]], id[w.triangles[t + 2]]});
      trianglePatch.push_back(p);
    }
  }
  return out;
}

std::vector<RemeshPatch> patchSnapshot(const Meshing& m, const MeshBuffers& out) {
  const Patches& work = m.patches;
  std::vector<RemeshPatch> res(work.size());
  uint32_t next = uint32_t(m.samples.cm.samples.size());
  for (size_t p = 0; p < work.size(); ++p) {
    const PatchWork& w = *work[p];
    RemeshPatch& r = res[p];
    r.layoutUv = w.flat.uv;
    r.layoutTriangles = w.pm.mesh.triangles;
    r.layoutInputFace = w.pm.faceInput;
    r.layoutFactor = w.flat.u;
    r.uv = w.planarPoints;
    r.triangles = w.triangles;
    r.outputVertex.resize(w.localToGlobal.size());
    for (size_t v = 0; v < w.localToGlobal.size(); ++v)
      r.outputVertex[v] = w.localToGlobal[v] != kNone ? w.localToGlobal[v] : next++;
  }
  if (next != out.vertexCount()) fail(Code::InternalError, Stage::Stitch, "patch snapshot does not match the stitched mesh");
  return res;
}


void addNonManifoldEdge(MeshBuffers& m, std::vector<uint32_t>& vertexFace, std::vector<uint8_t>& exemptVertex,
                        std::vector<uint32_t>& triPatch) {
  if (m.triangles.empty()) return;
  const uint32_t a = m.triangles[0], b = m.triangles[1], c = m.triangles[2], copy = uint32_t(m.vertexCount());
  for (int k = 0; k < 3; ++k) m.positions.push_back(m.positions[3 * size_t(c) + k]);
  if (!m.uvs.empty()) m.uvs.insert(m.uvs.end(), {m.uvs[2 * size_t(c)], m.uvs[2 * size_t(c) + 1]});
  m.triangles.insert(m.triangles.end(), {b, a, copy});
  vertexFace.push_back(vertexFace[c]);
  exemptVertex.push_back(0);
  triPatch.push_back(triPatch[0]);
}

}  // namespace conformesh::pipeline
