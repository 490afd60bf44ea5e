// conformesh — creases, not noise: which sharp edges of a tessellation are features.
//
// Pipeline stage "segment" (docs/ARCHITECTURE.md), first step. An edge whose dihedral angle
// exceeds the feature angle is a candidate. On CAD the candidates are creases: long chains of
// edges whose neighbourhood is flat or gently curved. On a coarse or noisy tessellation of a
// smooth surface (scans, organic models) many edges exceed any fixed angle: they are facets, not
// creases, and each one kept becomes a curve, so patches, exempt junctions and grading. Four
// tests tell them apart, the first per face, the others at once along a chain (hysteresis: a
// chain is kept or dropped whole):
//   * outliers: a face whose two candidate edges meet at a tip sharper than outlierTipDeg while
//     the faces across them bend by less than the feature angle: the face's three corners lie on
//     those two neighbours, so its own normal is the artifact (a needle whose normal its
//     vertices' noise swings, or a face folded over), and the two edges are no candidates,
//     unless one of them is on a line (below): a CAD face between two of its lines is real;
//     where the faces across do bend and the face is a cap (its other corner on the long edge
//     also below outlierTipDeg, so its third corner is obtuse and near that edge), one crease
//     passes the sliver on both sides: the long edge is no candidate, or the short one where
//     the long edge is on a line; likewise a flap: a face hanging on the boundary by one
//     candidate edge (its other two edges on the boundary) with both corners there below
//     outlierTipDeg, a sliver whose normal is noise and whose crease would only wall it off
//     behind two exempt corners;
//   * contrast: an edge's dihedral against the median dihedral of the edges around its two ends
//     (its own chain excluded): a crease stands out of a smooth neighbourhood, a facet of a
//     coarse surface does not;
//   * continuation: candidates at a vertex join one chain only where the chain goes on straight
//     (turn below continuationDeg, best pairs first), so the zigzags of noise fall apart into
//     short pieces;
//   * length: against the output's scale (minLength, about twice the target edge length), a
//     chain shorter than that is kept only as a bridge: it stands out and each of its free ends
//     touches the boundary or another kept or strongly standing-out chain; a long straight
//     chain of many edges is a line, whatever its contrast.
// Canny's hysteresis (1986) along chains; the contrast test follows the neighbourhood-relative
// sharpness of Hubeli & Gross (2001, Multiresolution feature extraction for unstructured meshes).
#pragma once

#include <cstdint>
#include <vector>

#include "features/edge_graph.h"

namespace conformesh::features {

struct CreaseOptions {
  //! Candidates: interior edges whose face normals differ by more than this (degrees).
  double featureAngleDeg = 40.0;
  //! Chains (absolute length) below this are kept only as bridges (see above). 0 keeps every
  //! candidate (no chain tests at all).
  double minLength = 0.0;
  //! Two candidates at a vertex continue one chain when the polyline turns by less (degrees).
  double continuationDeg = 45.0;
  //! An edge stands out when its dihedral is at least this times the median dihedral around it.
  double contrast = 3.0;
  //! ... and stands out strongly at this ratio (short chains need it).
  double strongContrast = 6.0;
  //! A chain of at least lineEdges edges and lineLengthFactor · minLength is a line, kept
  //! whatever its contrast (a CAD crease across a curved region whose other edges bend too).
  double lineLengthFactor = 4.0;
  uint32_t lineEdges = 5;
  //! Outlier faces (below) are looked for where their two candidates meet below this (degrees):
  //! the segmentation passes min(the output's angle bound, kSliverTipDeg): below the bound the
  //! wedge would be an exempt corner, and a face with a wider tip is no sliver.
  double outlierTipDeg = 30.0;
};

//! A face whose tips are all at least this wide (degrees) is no sliver: its normal is its
//! surface's, and the creases along it are the surface's own (the outlier tests do not look at
//! it whatever the angle bound).
constexpr double kSliverTipDeg = 30.0;

struct Creases {
  std::vector<uint8_t> edge;  //!< per edge: 1 for a crease
  uint32_t candidates = 0;    //!< edges above the feature angle
  uint32_t creaseEdges = 0;   //!< of those, kept
  uint32_t chains = 0;        //!< chains of candidates formed
  uint32_t keptChains = 0;
};

//! Detect the creases of `g`. Deterministic; O(edges · valence²). Throws Error(InvalidArgument)
//! for options out of range.
Creases detectCreases(const EdgeGraph& g, const CreaseOptions& options);

}  // namespace conformesh::features
