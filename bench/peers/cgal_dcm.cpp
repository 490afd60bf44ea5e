// Peer driver: CGAL discrete conformal map (Surface_mesh_parameterization,
// Discrete_conformal_map_parameterizer_3 — Eck et al. 1995 cotangent weights, a linear solve with
// the longest border fixed on a circle by arc length). No flips, no guarantee of a bijective map.
//
//   cgal_dcm IN.(obj|off) [-o OUT.off]     (OUT: the uv positions as a planar mesh, z = 0)
//
// Prints one JSON line: faces, seconds (the parameterize() call), invertedTriangles (uv
// triangles with the opposite orientation of the majority), peakRssBytes.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/Circular_border_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Discrete_conformal_map_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "peer_util.h"

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
typedef boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
typedef boost::graph_traits<Mesh>::halfedge_descriptor halfedge_descriptor;
namespace SMP = CGAL::Surface_mesh_parameterization;
namespace PMP = CGAL::Polygon_mesh_processing;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: cgal_dcm IN [-o OUT.off]\n");
    return 2;
  }
  try {
    std::string outPath = peer::arg(argc, argv, "-o");
    Mesh mesh;
    if (!PMP::IO::read_polygon_mesh(argv[1], mesh) || is_empty(mesh) || !CGAL::is_triangle_mesh(mesh))
      throw std::runtime_error("CGAL could not read a triangle mesh from the input");
    halfedge_descriptor border = PMP::longest_border(mesh).first;
    if (border == boost::graph_traits<Mesh>::null_halfedge()) throw std::runtime_error("the mesh has no border");
    auto uv = mesh.add_property_map<vertex_descriptor, K::Point_2>("v:uv").first;

    typedef SMP::Circular_border_arc_length_parameterizer_3<Mesh> Border;
    typedef SMP::Discrete_conformal_map_parameterizer_3<Mesh, Border> Parameterizer;
    double t0 = peer::now();
    SMP::Error_code err = SMP::parameterize(mesh, Parameterizer(), border, uv);
    double t1 = peer::now();
    if (err != SMP::OK) throw std::runtime_error(std::string("parameterize failed: ") + SMP::get_error_message(err));

    size_t pos = 0, neg = 0;
    for (auto f : faces(mesh)) {
      halfedge_descriptor h = halfedge(f, mesh);
      K::Point_2 a = uv[source(h, mesh)], b = uv[target(h, mesh)], c = uv[target(next(h, mesh), mesh)];
      double o = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
      (o > 0 ? pos : neg) += 1;
    }
    if (!outPath.empty()) {
      std::ofstream out(outPath);
      out.precision(17);
      out << "OFF\n" << num_vertices(mesh) << " " << num_faces(mesh) << " 0\n";
      for (auto v : vertices(mesh)) out << uv[v].x() << " " << uv[v].y() << " 0\n";
      for (auto f : faces(mesh)) {
        out << "3";
        for (auto v : vertices_around_face(halfedge(f, mesh), mesh)) out << " " << size_t(v);
        out << "\n";
      }
    }
    std::printf(
        "{\"tool\":\"cgal-discrete-conformal-map\",\"cgalVersion\":\"%s\",\"faces\":%zu,\"vertices\":%zu,"
        "\"seconds\":%s,\"invertedTriangles\":%zu,\"peakRssBytes\":%lld}\n",
        CGAL_VERSION_STR, size_t(num_faces(mesh)), size_t(num_vertices(mesh)), peer::num(t1 - t0).c_str(),
        std::min(pos, neg), peer::peakRssBytes());
    return 0;
  } catch (const std::exception& e) {
    std::printf("{\"tool\":\"cgal-discrete-conformal-map\",\"error\":\"%s\"}\n", e.what());
    return 1;
  }
}
