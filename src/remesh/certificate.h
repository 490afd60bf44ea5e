// conformesh — remesh stage 6: the 3D angle certificate of a stitched round. It finds the input's
// corners below the bound (the only triangles exempt from it), counts the triangles below the
// bound elsewhere and the stitch defects, and asks the patches for smaller triangles there.
#pragma once

#include <array>
#include <unordered_map>

#include "remesh/pipeline.h"

namespace conformesh::pipeline {

//! A triangle with a corner below this (degrees) has collapsed: never a wanted output.
constexpr double kCollapsedDeg = 1e-3;

//! Smallest corner angle of triangle t in degrees (quality::minMaxAngle's, the report's
//! measure); 0 for a degenerate triangle.
double triangleMinAngle(const MeshBuffers& m, size_t t);

//! Whether triangleMinAngle(m, t) < boundDeg, mostly without its atan2s: the corner cosines
//! u·v / (|u||v|), within a few ulp of the exact ones, decide when they are more than 1e-9 from
//! cosBound = cos(boundDeg) (|Δcos| ≤ |Δangle|, and the atan2 angles are within a few 1e-16 rad
//! of the exact ones); a triangle near the bound, or with sides near under- or overflow, is
//! measured.
bool minAngleBelow(const MeshBuffers& m, size_t t, double boundDeg, double cosBound);

//! The exempt corners: input vertices where the input's own feature or boundary curves make a
//! wedge below the bound. Cuts are ours (not features): a small angle where a cut meets a curve
//! is not exempt.
struct ExemptCorners {
  explicit ExemptCorners(double boundDeg);
  double boundDeg, cosBound;    //!< the angle bound and its cosine
  std::vector<uint8_t> vertex;  //!< per output vertex: an exempt corner (a curve sample)
  //! per curve sample: (exempt corner sample, curve) for each curve through it that ends at an
  //! exempt corner
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> wedgeCurves;
  std::unordered_map<uint32_t, double> wedgeDeg;  //!< exempt corner sample -> its wedge angle

  //! Find them (once, on the first stitched round of outVertices vertices: the samples of
  //! m's small corners) and list them in rep.exemptCorners.
  void find(const Surface& surf, const Meshing& m, size_t outVertices, RemeshReport& rep);
  //! Index the curves through every sample that end at a corner (after the samples change).
  void indexWedges(const Surface& surf, const CurveSamples& cs);
  //! The exempt corner triangle t belongs to, or kNone (see certificate.cpp).
  uint32_t cornerOf(const MeshBuffers& out, size_t t) const;
  //! Triangle t is below the bound and owned by no exempt corner.
  bool bad(const MeshBuffers& out, size_t t) const { return minAngleBelow(out, t, boundDeg, cosBound) && cornerOf(out, t) == kNone; }
};

//! Meshing::cornerWedgeDeg and smallCorner, once per call (boundDeg: the angle bound).
void measureCorners(const Surface& surf, double boundDeg, Meshing& m);

//! What a stitched round leaves to do.
struct Verdict {
  size_t bad = 0;        //!< triangles below the bound outside exempt corners
  size_t collapsed = 0;  //!< triangles with a corner below kCollapsedDeg
  std::vector<size_t> doubled;                    //!< stitch defects (remesh/stitch_defects.h)
  std::vector<std::array<size_t, 2>> chords;      //!< (triangle, corner) of chords two patches share
  size_t defects() const { return doubled.size() + chords.size(); }
};

//! Judge a stitched round (triPatch: the patch of each triangle); its three passes run side by
//! side on up to `threads` threads (RemeshOptions::threads), the same verdict for every count.
Verdict judge(const MeshBuffers& out, const std::vector<uint32_t>& triPatch, const ExemptCorners& exempt,
              unsigned threads = 1);

//! Ask the patches for what the verdict needs: a required point inside every stitch defect (its
//! patch then keeps its boundary when keepBoundary), a graded spot at every bad triangle.
void requestRefinement(const Verdict& verdict, const MeshBuffers& out, const std::vector<uint32_t>& triPatch,
                       const ExemptCorners& exempt, bool keepBoundary, Patches& patches);

}  // namespace conformesh::pipeline
