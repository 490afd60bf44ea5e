// conformesh — the rounds: every patch meshed until the patches agree on their curve samples
// (conforming rounds), optimized, the samples slid, the result stitched and judged by the 3D
// angle certificate, which asks for smaller triangles where it fails; the best round is kept.
#pragma once
#include <functional>

#include "remesh/certificate.h"
#include "remesh/pipeline.h"

namespace conformesh::pipeline {

//! The best stitched round: fewest stitch defects, then fewest collapsed triangles, then fewest
//! below the bound outside exempt corners.
struct BestRound {
  MeshBuffers out;
  std::vector<uint32_t> triPatch;    //!< per output triangle its patch
  std::vector<uint32_t> vertexFace;  //!< per output vertex an input face (stitch.h)
  size_t bad = 0;                    //!< its triangles below the bound outside exempt corners
  std::vector<RemeshPatch> patches;  //!< with RemeshOptions::returnPatches
};

//! The triangles a repair would leave below the bound in a round (repairing the copy it is given,
//! with m.samples and `exempt` set to that round's); empty: none is tried.
using RepairLeft = std::function<size_t(BestRound&)>;

//! Run the rounds on the flattened patches, up to RemeshOptions::maxCertificateRounds (and a
//! few more while a stitch defect is left); two rounds in a row without progress end them early
//! when repairLeft says the repair leaves nothing below the bound in the best one. m.samples
//! ends with the best round's curve samples; `exempt` is found on the first round. Each step's
//! time goes to its stage on `clock`; the first round reports progress as its stages, the later
//! ones as Stage::Certificate.
BestRound meshRounds(const Surface& surf, const RemeshOptions& opt, const Progress& progress, Meshing& m,
                     ExemptCorners& exempt, RemeshReport& rep, StageClock& clock, const RepairLeft& repairLeft = {});

}  // namespace conformesh::pipeline
