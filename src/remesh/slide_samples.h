// conformesh — remesh stage 4: curve samples slide along their input edges, in every patch that
// holds them at once, where that raises the smallest 3D angles around them.
#pragma once

#include "remesh/pipeline.h"

namespace conformesh::pipeline {

//! Curve samples slide along their input edge, in every patch that holds them at once
//! (a curve sample is shared by the patches on both sides): its 3D position moves along the input
//! edge and its planar position along that edge's image in each patch's layout. Candidates: toward
//! the 3D midpoint of its two neighbours along the curve (full and half step) and six points
//! spread over its free interval (no lift is needed on a curve, so the search is cheap); the best
//! kept one wins. A slide is kept under optimizePatch's rule over the union of the sample's stars
//! in all those patches: no planar triangle inverts, every 3D min angle stays >= the bound, and
//! their sum grows (stars with a triangle under the bound do not slide). The sample stays strictly
//! inside its input edge, so on the feature curve and on the surface, and never passes another
//! sample of that edge; the input curve's vertices between its two neighbours never get farther
//! from the chords. Two passes at most (the second over the samples next to one that slid).
//! Returns, per patch, the vertices whose star changed (empty when none): where to optimize again.
//! Adds the slides to rep.optimizeMoves.
std::vector<std::vector<uint8_t>> slideSamples(const Surface& surf, const RemeshOptions& opt, Meshing& m, RemeshReport& rep);

}  // namespace conformesh::pipeline
