// conformesh — remesh stage 7: the output measured. Angles (outside and at the exempt corners),
// edges, the topology check against the input, the feature curves kept, the distance to the
// input and, when asked, the sampled Hausdorff distance (quality/metrics.h).
#pragma once

#include "remesh/certificate.h"
#include "remesh/pipeline.h"

namespace conformesh::pipeline {

//! Fill rep's output fields from `out` (vertexFace: stitch()'s input face per output vertex, a
//! hint). The output's topology is checked against the input's: a difference (components,
//! boundary loops, Euler characteristic, non-manifold edges or vertices) fails with
//! InternalError, or comes back as the status with RemeshOptions::keepDefectiveOutput.
Status reportOutput(const Surface& surf, const CurveSamples& cs, const MeshBuffers& out, const std::vector<uint32_t>& vertexFace,
                    ExemptCorners& exempt, const RemeshOptions& opt, RemeshReport& rep);

}  // namespace conformesh::pipeline
