// conformesh — mesh quality measures: angles, edge lengths, topology, two-sided Hausdorff
// distance, feature preservation.
//
// These measure any triangle mesh given as flat arrays (our output, a peer's output, an input),
// so they tolerate what a validator would reject: degenerate and non-manifold triangles are
// counted, never an error. The remesh report (stage `report`) and the benchmark's quality tool
// (bench/quality_tool.cpp) both use them, so every mesher is judged by the same code.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "core/mesh_buffers.h"
#include "quality/aabb_tree.h"

namespace conformesh::quality {

//! Triangle angle statistics, in degrees. A degenerate triangle (zero area or a repeated vertex)
//! counts with min angle 0 and max angle 180: it is below every bound.
struct AngleStats {
  size_t triangles = 0;
  size_t degenerateTriangles = 0;
  double minAngle = 0;      //!< smallest corner angle of the mesh
  double maxAngle = 0;      //!< largest corner angle of the mesh
  double meanMinAngle = 0;  //!< mean over triangles of each triangle's smallest angle
  double pctBelow20 = 0;    //!< % of triangles whose smallest angle is < 20°
  double pctBelow26 = 0;    //!< ... < 26°
  double pctBelow30 = 0;    //!< ... < 30°
  //! Histogram of per-triangle min angles: bin i counts [5i, 5i+5) degrees, bin 12 is [60, 60].
  size_t minAngleHistogram[13] = {};
};

//! Smallest and largest corner angle (radians, each atan2(|u×v|, u·v) of the corner's sides) of
//! triangle f; false when degenerate (an index out of range, a repeated vertex, zero area, a
//! non-finite angle). One atan2 fewer than all three angles when the corner cosines tell them
//! apart: a cosine computed as u·v / (|u||v|) is within a few ulp of the exact one, and the atan2
//! form within a few 1e-16 rad of the exact angle, so cosines more than 1e-9 apart order the
//! computed angles as they order the exact ones (|Δcos| ≤ |Δangle|); otherwise all three are
//! computed.
bool minMaxAngle(const MeshBuffers& m, size_t f, double& mn, double& mx);

//! Angle statistics of every triangle. Indices must be < vertexCount() (precondition: the
//! caller validated the buffers; out-of-range triangles are counted as degenerate).
//! triangleMinAngles (optional): set to each triangle's smallest corner angle in radians,
//! atan2(|u×v|, u·v) of its two sides, NaN for a degenerate triangle.
AngleStats angleStats(const MeshBuffers& mesh, std::vector<double>* triangleMinAngles = nullptr);

//! Edge lengths (unique undirected edges) and the fraction of interior manifold edges that are
//! Delaunay in 3D (sum of the two opposite angles ≤ π, with 1e-12 slack).
struct EdgeStats {
  size_t edges = 0;
  double minLength = 0, maxLength = 0, meanLength = 0;
  double delaunayFraction = 1.0;  //!< over interior edges with exactly two faces
};
EdgeStats edgeStats(const MeshBuffers& mesh);

//! Combinatorial topology from the index arrays alone.
//! boundaryLoops counts connected components of the boundary-edge graph (two loops pinched at a
//! vertex count as one). genus = (2·components − χ − boundaryLoops) / 2, only meaningful when
//! nonManifoldEdges == 0 (else genus is −1). nonManifoldVertices: vertices whose triangles form
//! more than one fan, fans joined across edges of exactly two triangles (bow-ties; the ends of a
//! non-manifold edge usually count too); triangles that repeat a vertex are left out of the fans.
struct TopologySummary {
  size_t vertices = 0;  //!< referenced vertices
  size_t edges = 0;
  size_t faces = 0;
  size_t components = 0;  //!< edge-connected components of the referenced vertices
  size_t boundaryEdges = 0;
  size_t boundaryLoops = 0;
  size_t nonManifoldEdges = 0;  //!< edges with more than two faces
  size_t nonManifoldVertices = 0;
  long long euler = 0;          //!< V − E + F
  long long genus = -1;
};
TopologySummary topologySummary(const MeshBuffers& mesh);

//! edgeStats and topologySummary of one mesh, its edges grouped once for both.
struct EdgeTopology {
  EdgeStats edges;
  TopologySummary topology;
};
EdgeTopology edgeStatsAndTopology(const MeshBuffers& mesh);

//! Axis-aligned bounding box of the referenced vertices (all vertices if none are referenced).
Box3 boundingBox(const MeshBuffers& mesh);

//! Closest-point queries on a triangle mesh (AABB tree over its triangles). Keeps a reference to
//! the mesh: it must outlive the object.
class TriangleMeshDistance {
 public:
  explicit TriangleMeshDistance(const MeshBuffers& mesh, AabbSplit split = AabbSplit::Median);
  //! Squared distance from p to the mesh, and the closest triangle (primitive −1 and infinity
  //! when the mesh has no valid triangle). hint: a triangle likely near p (e.g. the previous
  //! query's answer), or −1; the distance is the same with or without it, only faster.
  //! stopSquared: answer the first triangle found (the hint first) at squared distance <=
  //! stopSquared, a witness that p is that close rather than its closest triangle; when no
  //! triangle is that close the answer is the closest. Negative (the default): always the closest.
  ClosestHit closest(const Vec3& p, int64_t hint = -1, double stopSquared = -1.0) const;
  //! Squared distance from q to triangle f alone (an upper bound of the mesh's; infinity for an
  //! invalid triangle).
  double faceDistanceSquared(uint32_t f, const Vec3& q) const;

 private:
  const MeshBuffers& mesh_;
  AabbTree tree_;
};

struct HausdorffOptions {
  //! Points sampled on each surface, area-weighted, in addition to its vertices.
  size_t samplesPerSide = 200000;
  uint64_t seed = 1;  //!< fixed seed: results are deterministic (same on native and WASM)
  //! Also the mean distances (every sample searched for its closest triangle). Off: the means
  //! are −1 and the maxima the same, found faster (most samples need no full search).
  bool computeMean = false;
  //! Optional, for speed only (the result is the same without it): for each vertex of A, a
  //! triangle of B likely near it, e.g. the remesher's input face of each output vertex (an
  //! index ≥ B's triangle count: none). Ignored unless it has one entry per vertex of A.
  const std::vector<uint32_t>* nearTriangleOfVertexA = nullptr;
  //! Threads for the maxima (core/parallel_for.h; 0: the hardware's concurrency). The samples
  //! are searched in chunks of a fixed size, each with a running max of its own: the same
  //! searches and the same maxima for every count.
  unsigned threads = 1;
};

//! The points a Hausdorff distance is measured from on mesh m: every referenced vertex (in index
//! order); with count > 0 the midpoints of the boundary edges and of the edges bending by more
//! than 20° (once each, in the order of the sorted vertex pairs) and `count` area-weighted random
//! points, triangle by triangle (the floor of each
//! triangle's expected count plus a random rounding; uniform in the triangle, Osada et al. 2002),
//! from a SplitMix64 stream seeded with `seed`: the same points on every platform.
std::vector<Vec3> surfaceSamples(const MeshBuffers& m, size_t count, uint64_t seed);

//! Sampled two-sided Hausdorff distance between meshes A and B (absolute units).
//!
//! What it certifies: aToB is the largest, over the samples p of A (surfaceSamples(a,
//! samplesPerSide, seed)), of the distance from p to B's closest triangle as the AABB tree search
//! computes it in double (Ericson's closest point, §5.1.5; the same per-triangle values a brute
//! force over every triangle gives); bToA likewise over surfaceSamples(b, samplesPerSide, seed + 1)
//! against A. Each is attained by a point of a surface, so hausdorff = max(aToB, bToA) is a lower
//! bound of the true two-sided Hausdorff distance (up to that rounding), converging to it as the
//! samples grow; the vertices are always among the samples. computeMean does not change the
//! maxima: without it a sample is either searched for its closest triangle or shown, by a triangle
//! of the other mesh at most the running maximum away, unable to raise it (early breaking; Taha &
//! Hanbury 2015, "An efficient algorithm for calculating the exact Hausdorff distance", IEEE TPAMI
//! 37(11)), so the maxima are those of the full search, found in a fraction of its time.
//! `diagonal` is B's bounding-box diagonal (B is the reference, normally the input) and
//! `relative` = hausdorff / diagonal. Deterministic: the same value natively and in WASM, run
//! after run, on any number of threads.
struct HausdorffResult {
  double aToB = 0, bToA = 0;          //!< max one-sided distances
  double meanAToB = 0, meanBToA = 0;  //!< mean one-sided distances (−1 without computeMean)
  double hausdorff = 0;               //!< max(aToB, bToA)
  double diagonal = 0;
  double relative = 0;
  size_t samplesA = 0, samplesB = 0;
};
HausdorffResult hausdorffDistance(const MeshBuffers& a, const MeshBuffers& b,
                                  const HausdorffOptions& options = {});

//! hausdorffDistance in two steps, for a caller that runs the preparation beside work of its own:
//! hausdorffJob(w, a, b, options, job) for every job in [0, kJobs), in any order and on any
//! threads (each writes its own part of w: 0 and 1 the two trees, the larger mesh's first, 2 and
//! 3 the two sample sets and the order they are searched in), then hausdorffMeasure: the same
//! result as hausdorffDistance.
struct HausdorffWork {
  static constexpr size_t kJobs = 4;
  std::vector<Vec3> samplesA, samplesB;
  std::vector<std::pair<uint64_t, uint32_t>> orderA, orderB;  //!< (Morton code, sample) sorted
  std::unique_ptr<TriangleMeshDistance> toA, toB;
};
void hausdorffJob(HausdorffWork& w, const MeshBuffers& a, const MeshBuffers& b, const HausdorffOptions& options,
                  size_t job);
HausdorffResult hausdorffMeasure(const HausdorffWork& w, const MeshBuffers& a, const MeshBuffers& b,
                                 const HausdorffOptions& options);

//! How well the output keeps the reference's sharp features. Reference feature edges: interior
//! edges (two faces) with dihedral angle > `featureAngle` degrees. Each is sampled at
//! `samplesPerEdge` interior points; a sample is kept when it lies within `tolerance` (absolute)
//! of an output feature edge (dihedral > `outputFeatureAngle`).
struct FeatureOptions {
  double featureAngle = 60.0;
  double outputFeatureAngle = 30.0;
  int samplesPerEdge = 4;
  double tolerance = 0;  //!< absolute; 0 = 1e-4 · reference bbox diagonal
};
struct FeatureResult {
  size_t referenceFeatureEdges = 0;
  size_t outputFeatureEdges = 0;
  size_t samples = 0;
  size_t kept = 0;
  double fractionKept = 1.0;  //!< 1 when the reference has no feature edge
  double maxDistance = 0;     //!< largest sample distance to the output feature edges
};
FeatureResult featurePreservation(const MeshBuffers& output, const MeshBuffers& reference,
                                  const FeatureOptions& options = {});

}  // namespace conformesh::quality
