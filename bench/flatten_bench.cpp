// Benchmark and acceptance run of the flatten stage (issue 4).
// Usage:
//  bench_flatten IN [--boundary circle|free] [--repeat N] [--pullback]
//     Flatten the mesh file IN N times (default 3) in one process; one JSON line per run and a
//     last line with the medians: seconds (flatten() wall), cpuSeconds (process CPU of the
//     call), iterations, maxCurvatureError, flips, invertedTriangles, and the flow's phases.
//     The same program runs under Node (build/wasm/bench_flatten.cjs) for the WASM ratio.
//  bench_flatten [--quick]
//  1. face.obj subdivided once 1-to-4 (~207k faces): flatten (circle and free boundary), time per
//     phase, Newton iterations, flips. Target: <= 2 s native (peer: CGAL's linear discrete
//     conformal map 3.8 s; Campen et al. 2021 metric only 3.8-5.1 s on this machine).
//  2. Every disk / multiply connected data mesh: converges, 0 inverted triangles, and the
//     pull-back of 10,000 random planar points lands on the input surface (<= 1e-9 bbox diag).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "conformesh.h"

using namespace conformesh;

namespace {

MeshBuffers readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in.good()) fail(Code::InvalidArgument, Stage::Api, "bench_flatten: cannot open " + path);
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ReadOptions ro;
  ro.fileName = path;
  return readMesh(bytes, ro).mesh;
}

MeshBuffers readData(const std::string& name) { return readFile(std::string(CONFORMESH_DATA_DIR) + "/" + name); }

double median(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  return x.empty() ? 0.0 : (x.size() % 2 ? x[x.size() / 2] : 0.5 * (x[x.size() / 2 - 1] + x[x.size() / 2]));
}

// One file, timed runs, JSON lines (the interface bench/run.mjs reads).
int timeFile(const std::string& path, BoundaryCondition bc, int repeat, bool pullback) {
  const MeshBuffers M = readFile(path);
  FlattenOptions o;
  o.boundary = bc;
  o.pullback = pullback;
  std::vector<double> wall, cpu;
  FlattenReport last;
  for (int r = 0; r < repeat; ++r) {
    const std::clock_t c0 = std::clock();
    FlatPatch P = flatten(M, o);
    cpu.push_back(double(std::clock() - c0) / CLOCKS_PER_SEC);
    wall.push_back(P.report.seconds);
    last = P.report;
    const auto& F = last.flowProfile;
    std::printf("{\"run\":%d,\"seconds\":%.4f,\"cpuSeconds\":%.4f,\"flow\":%.4f,\"layout\":%.4f,\"overlay\":%.4f,"
                "\"flips\":%.4f,\"angles\":%.4f,\"assemble\":%.4f,\"analyze\":%.4f,\"factor\":%.4f,\"solve\":%.4f,"
                "\"evaluations\":%d,\"analyses\":%d,\"factorizations\":%d,\"solves\":%d}\n",
                r, wall.back(), cpu.back(), last.secondsFlow, last.secondsLayout, last.secondsOverlay, F.flips, F.angles,
                F.assemble, F.analyze, F.factor, F.solve, F.evaluations, F.analyses, F.factorizations, F.solves);
    std::fflush(stdout);
  }
  std::printf("{\"input\":\"%s\",\"boundary\":\"%s\",\"faces\":%zu,\"repeat\":%d,\"seconds\":%.4f,\"secondsMin\":%.4f,"
              "\"cpuSeconds\":%.4f,\"iterations\":%d,\"maxCurvatureError\":%.3e,\"flips\":%lld,\"euclideanFlips\":%lld,"
              "\"invertedTriangles\":%d,\"areaDistortionRange\":%.4e}\n",
              path.c_str(), bc == BoundaryCondition::Free ? "free" : "circle", M.triangleCount(), repeat, median(wall),
              *std::min_element(wall.begin(), wall.end()), median(cpu), last.iterations, last.maxCurvatureError, last.flips,
              last.euclideanFlips, last.invertedTriangles, last.areaDistortionRange);
  return 0;
}

MeshBuffers subdivide(const MeshBuffers& M) {
  MeshBuffers S;
  S.positions = M.positions;
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
  auto midpoint = [&](uint32_t a, uint32_t b) {
    auto key = std::make_pair(std::min(a, b), std::max(a, b));
    auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    const uint32_t id = uint32_t(S.positions.size() / 3);
    for (int k = 0; k < 3; ++k) S.positions.push_back(0.5 * (M.positions[3 * a + k] + M.positions[3 * b + k]));
    mid[key] = id;
    return id;
  };
  for (size_t f = 0; f < M.triangleCount(); ++f) {
    const uint32_t a = M.triangles[3 * f], b = M.triangles[3 * f + 1], c = M.triangles[3 * f + 2];
    const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    S.triangles.insert(S.triangles.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
  }
  return S;
}

double diag(const MeshBuffers& M) {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (size_t v = 0; v < M.vertexCount(); ++v)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], M.positions[3 * v + k]);
      hi[k] = std::max(hi[k], M.positions[3 * v + k]);
    }
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

// Distance from q to the plane-clamped triangle: q is a convex combination of the triangle's
// vertices by construction, so we check how far it is from that combination recomputed.
double landError(const MeshBuffers& M, const PullbackPoint& q) {
  double p[3] = {0, 0, 0};
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < 3; ++c) p[c] += q.bary[k] * M.positions[3 * size_t(M.triangles[3 * q.face + k]) + c];
  double mn = std::min(q.bary[0], std::min(q.bary[1], q.bary[2]));
  return std::hypot(p[0] - q.position[0], p[1] - q.position[1], p[2] - q.position[2]) + (mn < 0 ? -mn : 0.0);
}

void report(const char* name, const MeshBuffers& M, const FlatPatch& P, int samples) {
  const auto& R = P.report;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(0, 1);
  int located = 0;
  double worst = 0, worstMargin = 0;
  const double d = diag(M);
  const auto t0 = std::chrono::steady_clock::now();
  for (int s = 0; s < samples; ++s) {
    const size_t t = size_t(U(rng) * P.layout.triangleCount()) % P.layout.triangleCount();
    double a = U(rng), b = U(rng);
    if (a + b > 1) {
      a = 1 - a;
      b = 1 - b;
    }
    const double* p0 = &P.layout.positions[3 * size_t(P.layout.triangles[3 * t])];
    const double* p1 = &P.layout.positions[3 * size_t(P.layout.triangles[3 * t + 1])];
    const double* p2 = &P.layout.positions[3 * size_t(P.layout.triangles[3 * t + 2])];
    PullbackPoint q;
    if (!P.pullback.locate(p0[0] + a * (p1[0] - p0[0]) + b * (p2[0] - p0[0]), p0[1] + a * (p1[1] - p0[1]) + b * (p2[1] - p0[1]), q))
      continue;
    ++located;
    worst = std::max(worst, landError(M, q) / d);
    worstMargin = std::min(worstMargin, q.margin);
  }
  const double tq = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%-22s %7zu faces  its %3d  err %.1e  flips %6lld+%6lld  %.3f s (flow %.3f layout %.3f overlay %.3f)  inv %d  bx %d  "
              "area %.1e  qc max %.2f mean %.3f  pull-back %d/%d worst %.1e margin %.1e (%.2f us/pt)\n",
              name, M.triangleCount(), R.iterations, R.maxCurvatureError, R.euclideanFlips, R.flips, R.seconds, R.secondsFlow,
              R.secondsLayout, R.secondsOverlay, R.invertedTriangles, R.boundaryCrossings, R.areaDistortionRange,
              R.angleDistortionMax, R.angleDistortionMean, located, samples, worst, worstMargin, 1e6 * tq / std::max(1, samples));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && argv[1][0] != '-') {
    BoundaryCondition bc = BoundaryCondition::Circle;
    int repeat = 3;
    bool pullback = false;
    for (int i = 2; i < argc; ++i) {
      if (!std::strcmp(argv[i], "--boundary") && i + 1 < argc) {
        ++i;
        bc = std::strcmp(argv[i], "free") == 0 ? BoundaryCondition::Free : BoundaryCondition::Circle;
      } else if (!std::strcmp(argv[i], "--repeat") && i + 1 < argc) {
        repeat = std::max(1, std::atoi(argv[++i]));
      } else if (!std::strcmp(argv[i], "--pullback")) {
        pullback = true;
      } else {
        std::fprintf(stderr, "usage: bench_flatten IN [--boundary circle|free] [--repeat N] [--pullback] | bench_flatten [--quick]\n");
        return 2;
      }
    }
    try {
      return timeFile(argv[1], bc, repeat, pullback);
    } catch (const Error& e) {
      std::printf("{\"error\":\"%s\",\"message\":\"%s\"}\n", codeName(e.code()), e.what());
      return 1;
    }
  }
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  MeshBuffers face = readData("face.obj");
  MeshBuffers face2 = subdivide(face);
  for (BoundaryCondition bc : {BoundaryCondition::Free, BoundaryCondition::Circle}) {
    for (bool pull : {false, true}) {
      FlattenOptions o;
      o.boundary = bc;
      o.pullback = pull;
      try {
        FlatPatch P = flatten(face2, o);
        char name[64];
        std::snprintf(name, sizeof name, "face/4 %s%s", bc == BoundaryCondition::Free ? "free" : "circle", pull ? "+overlay" : "");
        report(name, face2, P, pull ? 10000 : 0);
      } catch (const Error& e) {
        std::printf("face/4: %s %s\n", codeName(e.code()), e.what());
      }
    }
    if (quick) break;
  }
  if (quick) return 0;
  const char* names[] = {"face.obj", "camelhead.off", "alligator.obj", "holes.off", "mech-holes-shark.off", "stanford-bunny.obj", "blade.off"};
  for (const char* n : names) {
    MeshBuffers M = readData(n);
    for (BoundaryCondition bc : {BoundaryCondition::Free, BoundaryCondition::Circle}) {
      FlattenOptions o;
      o.boundary = bc;
      char name[64];
      std::snprintf(name, sizeof name, "%s %s", n, bc == BoundaryCondition::Free ? "free" : "circle");
      try {
        FlatPatch P = flatten(M, o);
        report(name, M, P, 10000);
      } catch (const Error& e) {
        std::printf("%-22s %s: %s\n", name, codeName(e.code()), e.what());
      }
    }
  }
  return 0;
}
