// Peer driver: CGAL Mesh_2 (Delaunay_mesher_2) on a Triangle .poly file.
//
//   cgal_mesh2 IN.poly [--min-angle DEG] [--max-edge L] [-o OUT.off]
//
// Prints one JSON line: triangles, vertices, minAngle (degrees, over the meshed domain),
// domainArea, cdtSeconds (constrained Delaunay triangulation of the PSLG), refineSeconds,
// seconds (both), peakRssBytes. CGAL's shape criterion takes b = sin²(min angle) (its bound B on
// circumradius / shortest edge is sqrt(1/(4b)), and sin(alpha_min) = 1/(2B)); the size criterion is
// a bound on every edge length (0 = none). Hole seeds of the .poly mark components not meshed.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <list>
#include <map>
#include <string>

#include "peer_util.h"

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Triangulation_vertex_base_2<K> Vb;
typedef CGAL::Delaunay_mesh_face_base_2<K> Fb;
typedef CGAL::Triangulation_data_structure_2<Vb, Fb> Tds;
typedef CGAL::Constrained_Delaunay_triangulation_2<K, Tds> CDT;
typedef CGAL::Delaunay_mesh_size_criteria_2<CDT> Criteria;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: cgal_mesh2 IN.poly [--min-angle DEG] [--max-edge L] [-o OUT.off]\n");
    return 2;
  }
  try {
    const double pi = 3.14159265358979323846;
    double minAngle = std::stod(peer::arg(argc, argv, "--min-angle", "20.7"));
    double maxEdge = std::stod(peer::arg(argc, argv, "--max-edge", "0"));
    std::string outPath = peer::arg(argc, argv, "-o");
    peer::Poly poly = peer::readPoly(argv[1]);

    double t0 = peer::now();
    CDT cdt;
    std::vector<CDT::Vertex_handle> vh(poly.xy.size() / 2);
    for (size_t i = 0; i < vh.size(); ++i) vh[i] = cdt.insert(K::Point_2(poly.xy[2 * i], poly.xy[2 * i + 1]));
    for (auto& s : poly.seg)
      if (vh[s.first] != vh[s.second]) cdt.insert_constraint(vh[s.first], vh[s.second]);
    double t1 = peer::now();
    std::list<K::Point_2> seeds;
    for (size_t i = 0; i + 1 < poly.holes.size(); i += 2) seeds.push_back(K::Point_2(poly.holes[i], poly.holes[i + 1]));
    double s = std::sin(minAngle * pi / 180.0);
    CGAL::refine_Delaunay_mesh_2(cdt, seeds.begin(), seeds.end(), Criteria(s * s, maxEdge), false);
    double t2 = peer::now();

    size_t tris = 0;
    double worst = 180, area = 0;
    std::map<CDT::Vertex_handle, size_t> index;
    std::vector<std::array<size_t, 3>> faces;
    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
      if (!f->is_in_domain()) continue;
      ++tris;
      K::Point_2 p[3] = {f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point()};
      for (int k = 0; k < 3; ++k) {
        double ux = p[(k + 1) % 3].x() - p[k].x(), uy = p[(k + 1) % 3].y() - p[k].y();
        double vx = p[(k + 2) % 3].x() - p[k].x(), vy = p[(k + 2) % 3].y() - p[k].y();
        double ang = std::atan2(std::fabs(ux * vy - uy * vx), ux * vx + uy * vy) * 180 / pi;
        worst = std::min(worst, ang);
      }
      area += 0.5 * std::fabs((p[1].x() - p[0].x()) * (p[2].y() - p[0].y()) - (p[1].y() - p[0].y()) * (p[2].x() - p[0].x()));
      if (!outPath.empty()) {
        std::array<size_t, 3> t{};
        for (int k = 0; k < 3; ++k) t[k] = index.emplace(f->vertex(k), index.size()).first->second;
        faces.push_back(t);
      }
    }
    if (!outPath.empty()) {
      std::vector<K::Point_2> pts(index.size());
      for (auto& kv : index) pts[kv.second] = kv.first->point();
      std::ofstream out(outPath);
      out.precision(17);
      out << "OFF\n" << pts.size() << " " << faces.size() << " 0\n";
      for (auto& p : pts) out << p.x() << " " << p.y() << " 0\n";
      for (auto& t : faces) out << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
    }
    std::printf(
        "{\"tool\":\"cgal-mesh2\",\"cgalVersion\":\"%s\",\"minAngleBound\":%s,\"maxEdge\":%s,\"triangles\":%zu,"
        "\"vertices\":%zu,\"minAngle\":%s,\"domainArea\":%s,\"cdtSeconds\":%s,\"refineSeconds\":%s,\"seconds\":%s,"
        "\"peakRssBytes\":%lld}\n",
        CGAL_VERSION_STR, peer::num(minAngle).c_str(), peer::num(maxEdge).c_str(), tris,
        size_t(cdt.number_of_vertices()), peer::num(worst).c_str(), peer::num(area).c_str(),
        peer::num(t1 - t0).c_str(), peer::num(t2 - t1).c_str(), peer::num(t2 - t0).c_str(), peer::peakRssBytes());
    return 0;
  } catch (const std::exception& e) {
    std::printf("{\"tool\":\"cgal-mesh2\",\"error\":\"%s\"}\n", e.what());
    return 1;
  }
}
