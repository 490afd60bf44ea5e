// Peer driver: CGAL isotropic remeshing (Polygon_mesh_processing::isotropic_remeshing,
// Botsch–Kobbelt 2004 style split/collapse/flip/relax) with sharp edges protected.
//
//   cgal_remesh IN.(off|obj|stl|ply) -o OUT.off [--edge-length-rel R | --edge-length L]
//               [--feature-angle DEG] [--iterations N]
//
// Sharp edges: dihedral angle ≥ feature angle (default 60°), found by
// PMP::detect_sharp_edges and passed as constrained edges: they may be split or collapsed along
// their polyline but never flipped or moved off it. Target edge length: R × bounding-box diagonal
// (default R = 0.004), or L. Prints one JSON line; the quality of OUT is measured by our own tool.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "peer_util.h"

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
namespace PMP = CGAL::Polygon_mesh_processing;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: cgal_remesh IN -o OUT.off [--edge-length-rel R | --edge-length L] [--feature-angle D] [--iterations N]\n");
    return 2;
  }
  try {
    std::string outPath = peer::arg(argc, argv, "-o");
    double rel = std::stod(peer::arg(argc, argv, "--edge-length-rel", "0.004"));
    double abs = std::stod(peer::arg(argc, argv, "--edge-length", "0"));
    double featureAngle = std::stod(peer::arg(argc, argv, "--feature-angle", "60"));
    unsigned iterations = unsigned(std::stoul(peer::arg(argc, argv, "--iterations", "3")));

    Mesh mesh;
    if (!PMP::IO::read_polygon_mesh(argv[1], mesh) || is_empty(mesh) || !CGAL::is_triangle_mesh(mesh))
      throw std::runtime_error("CGAL could not read a triangle mesh from the input");
    size_t inFaces = num_faces(mesh);
    CGAL::Bbox_3 bb = PMP::bbox(mesh);
    double diag = std::sqrt((bb.xmax() - bb.xmin()) * (bb.xmax() - bb.xmin()) +
                            (bb.ymax() - bb.ymin()) * (bb.ymax() - bb.ymin()) +
                            (bb.zmax() - bb.zmin()) * (bb.zmax() - bb.zmin()));
    double target = abs > 0 ? abs : rel * diag;

    double t0 = peer::now();
    auto eif = get(CGAL::edge_is_feature, mesh);
    PMP::detect_sharp_edges(mesh, featureAngle, eif);
    size_t sharp = 0;
    for (auto e : edges(mesh)) sharp += get(eif, e) ? 1 : 0;
    double t1 = peer::now();
    PMP::isotropic_remeshing(faces(mesh), target, mesh,
                             PMP::parameters::number_of_iterations(iterations)
                                 .edge_is_constrained_map(eif)
                                 .protect_constraints(false));
    double t2 = peer::now();
    mesh.collect_garbage();
    if (!outPath.empty() && !CGAL::IO::write_polygon_mesh(outPath, mesh, CGAL::parameters::stream_precision(17)))
      throw std::runtime_error("cannot write " + outPath);
    std::printf(
        "{\"tool\":\"cgal-isotropic-remeshing\",\"cgalVersion\":\"%s\",\"inputTriangles\":%zu,\"diagonal\":%s,"
        "\"targetEdgeLength\":%s,\"featureAngle\":%s,\"sharpEdges\":%zu,\"iterations\":%u,\"triangles\":%zu,"
        "\"vertices\":%zu,\"featureSeconds\":%s,\"remeshSeconds\":%s,\"seconds\":%s,\"peakRssBytes\":%lld}\n",
        CGAL_VERSION_STR, inFaces, peer::num(diag).c_str(), peer::num(target).c_str(), peer::num(featureAngle).c_str(),
        sharp, iterations, size_t(num_faces(mesh)), size_t(num_vertices(mesh)), peer::num(t1 - t0).c_str(),
        peer::num(t2 - t1).c_str(), peer::num(t2 - t0).c_str(), peer::peakRssBytes());
    return 0;
  } catch (const std::exception& e) {
    std::printf("{\"tool\":\"cgal-isotropic-remeshing\",\"error\":\"%s\"}\n", e.what());
    return 1;
  }
}
