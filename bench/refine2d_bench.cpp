// bench_refine2d — planar Delaunay refinement throughput and memory (native and WASM).
//
//   bench_refine2d IN.poly [--min-angle D] [--max-area A | --max-edge L] [--repeat N]
//   bench_refine2d --suite [--data DIR] [--repeat N]
//
// One JSON line per run on stdout: input, options, triangles, vertices, minAngle,
// exemptTriangles, seconds (wall time of refinePslg: CDT + refinement + output arrays; input
// parsing excluded), cpuSeconds (process CPU time of the same span: on a shared machine it is
// the steadier number), trianglesPerSecond (from seconds), peakBytes and bytesPerTriangle
// (native: getrusage max resident set; WASM: the heap size, which only grows; both are
// process-wide maxima, so in --suite only the first line is that run alone). --suite runs
// square_holes and wiggly5000 at 30 degrees with the area bound that gives ~1M triangles, and
// the four angles without size bound. The last line of a run is the median of --repeat runs.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "planar/poly_io.h"
#include "planar/refine.h"

#ifdef __EMSCRIPTEN__
#include <emscripten/heap.h>
#else
#include <sys/resource.h>
#endif

using namespace conformesh;
using namespace conformesh::planar;

namespace {

double peakBytes() {
#ifdef __EMSCRIPTEN__
  return double(emscripten_get_heap_size());
#else
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return double(ru.ru_maxrss) * 1024.0;
#endif
}

std::vector<uint8_t> readBytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) {
    std::fprintf(stderr, "bench_refine2d: cannot open %s\n", path.c_str());
    std::exit(2);
  }
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

struct Run {
  size_t triangles = 0, vertices = 0, exempt = 0;
  double minAngle = 0, seconds = 0, cpu = 0, peak = 0;
};

void runOne(const std::string& path, const RefineOptions& o, int repeat) {
  Pslg in = readPoly(readBytes(path));
  std::vector<Run> runs;
  for (int k = 0; k < repeat; ++k) {
    std::clock_t c0 = std::clock();
    auto w0 = std::chrono::steady_clock::now();
    RefineResult r = refinePslg(in, o);
    double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
    double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
    Run x;
    x.triangles = r.mesh.triangleCount();
    x.vertices = r.mesh.vertexCount();
    x.exempt = r.exemptTriangles;
    x.minAngle = r.minAngleDeg;
    x.seconds = wall;
    x.cpu = cpu;
    x.peak = peakBytes();
    runs.push_back(x);
    if (!r.status.ok()) std::fprintf(stderr, "bench_refine2d: %s\n", r.status.message.c_str());
  }
  auto med = [&](auto key) {
    std::vector<double> v;
    for (const Run& r : runs) v.push_back(key(r));
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  const Run& last = runs.back();
  double secs = med([](const Run& r) { return r.seconds; });
  double cpu = med([](const Run& r) { return r.cpu; });
  std::string name = path.substr(path.find_last_of('/') + 1);
  std::printf(
      "{\"bench\":\"refine2d\",\"target\":\"%s\",\"input\":\"%s\",\"minAngleBound\":%g,\"maxArea\":%g,\"maxEdge\":%g,"
      "\"repeat\":%d,\"triangles\":%zu,\"vertices\":%zu,\"minAngle\":%.6f,\"exemptTriangles\":%zu,"
      "\"seconds\":%.6f,\"cpuSeconds\":%.6f,\"trianglesPerSecond\":%.0f,\"trianglesPerCpuSecond\":%.0f,"
      "\"peakBytes\":%.0f,\"bytesPerTriangle\":%.1f}\n",
#ifdef __EMSCRIPTEN__
      "wasm",
#else
      "native",
#endif
      name.c_str(), o.minAngleDeg, o.maxArea, o.maxEdge, repeat, last.triangles, last.vertices, last.minAngle,
      last.exempt, secs, cpu, double(last.triangles) / secs, double(last.triangles) / cpu, last.peak,
      last.peak / double(last.triangles));
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> a(argv + 1, argv + argc);
  RefineOptions o;
  int repeat = 1;
  bool suite = false;
  std::string input, data = CONFORMESH_DATA_DIR;
  for (size_t i = 0; i < a.size(); ++i) {
    auto val = [&]() -> std::string {
      if (i + 1 >= a.size()) {
        std::fprintf(stderr, "bench_refine2d: %s needs a value\n", a[i].c_str());
        std::exit(2);
      }
      return a[++i];
    };
    if (a[i] == "--min-angle") o.minAngleDeg = std::stod(val());
    else if (a[i] == "--max-area") o.maxArea = std::stod(val());
    else if (a[i] == "--max-edge") o.maxEdge = std::stod(val());
    else if (a[i] == "--repeat") repeat = std::max(1, std::stoi(val()));
    else if (a[i] == "--data") data = val();
    else if (a[i] == "--suite") suite = true;
    else input = a[i];
  }
  try {
    if (!suite) {
      if (input.empty()) {
        std::fprintf(stderr, "usage: bench_refine2d IN.poly [--min-angle D] [--max-area A | --max-edge L] [--repeat N]\n"
                             "       bench_refine2d --suite [--data DIR] [--repeat N]\n");
        return 2;
      }
      runOne(input, o, repeat);
      return 0;
    }
    // ~1M output triangles at 30 degrees (areas measured: ~0.62·maxArea per triangle).
    const struct {
      const char* name;
      double maxArea;
    } big[] = {{"square_holes", 1.4e-6}, {"wiggly5000", 5.4e-6}, {"alligator_s3_lscm", 1.35e-7}};
    for (const auto& b : big) {
      RefineOptions x;
      x.maxArea = b.maxArea;
      runOne(data + "/pslg/" + b.name + ".poly", x, repeat);
    }
    for (const char* n : {"square_holes", "wiggly5000", "alligator_s3_lscm"})
      for (double th : {20.7, 26.0, 30.0, 33.0}) {
        RefineOptions x;
        x.minAngleDeg = th;
        runOne(data + "/pslg/" + n + ".poly", x, repeat);
      }
  } catch (const Error& e) {
    std::fprintf(stderr, "bench_refine2d: %s\n", e.what());
    return 1;
  }
  return 0;
}
