// Benchmark: building the halfedge mesh, validate() and meshInfo() on a 1M-triangle mesh.
// Usage: bench_validate [triangles (default 1000000)] [repeats (default 5)]
// Prints the median wall time of each, for the mesh in generation order and with its vertices
// and triangles shuffled (no memory locality). Target: halfedge build well under 1 s natively.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <numeric>
#include <random>
#include <vector>

#include "conformesh.h"

using namespace conformesh;

namespace {

// Median wall time and median process CPU time (the latter is less disturbed by other processes
// on a shared machine).
struct Timing {
  double wall, cpu;
};
Timing median(int repeats, const std::function<void()>& run) {
  std::vector<double> wall, cpu;
  for (int r = 0; r < repeats; ++r) {
    auto t0 = std::chrono::steady_clock::now();
    std::clock_t c0 = std::clock();
    run();
    cpu.push_back(double(std::clock() - c0) / CLOCKS_PER_SEC);
    wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(wall.begin(), wall.end());
  std::sort(cpu.begin(), cpu.end());
  return {wall[wall.size() / 2], cpu[cpu.size() / 2]};
}

MeshBuffers shuffled(const MeshBuffers& m) {
  std::mt19937 rng(1);
  std::vector<uint32_t> perm(m.vertexCount()), order(m.triangleCount());
  std::iota(perm.begin(), perm.end(), 0u);
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(perm.begin(), perm.end(), rng);
  std::shuffle(order.begin(), order.end(), rng);
  MeshBuffers out;
  out.positions.resize(m.positions.size());
  for (size_t v = 0; v < perm.size(); ++v)
    for (int k = 0; k < 3; ++k) out.positions[3 * perm[v] + k] = m.positions[3 * v + k];
  out.triangles.reserve(m.triangles.size());
  for (uint32_t f : order)
    for (int i = 0; i < 3; ++i) out.triangles.push_back(perm[m.triangles[3 * f + i]]);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const long target = argc > 1 ? std::atol(argv[1]) : 1000000;
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 5;
  const int n = std::max(3, int(std::lround(std::sqrt(double(target) / 2.0))));
  MeshBuffers grid = makeTorus(n, n, 2.0, 0.7);
  MeshBuffers shuffledGrid = shuffled(grid);
  std::printf("torus %d x %d: %zu vertices, %zu triangles, median of %d runs\n", n, n, grid.vertexCount(),
              grid.triangleCount(), repeats);
  std::printf("seconds, wall (cpu)\n%-10s %18s %18s %18s\n", "order", "halfedges", "validate", "meshInfo");
  for (const auto* m : {&grid, &shuffledGrid}) {
    Timing tb = median(repeats, [&] {
      HalfedgeMesh h = HalfedgeMesh::fromTriangles(m->vertexCount(), m->triangles);
      if (h.faceCount() != m->triangleCount()) std::abort();
    });
    Timing tv = median(repeats, [&] {
      ValidatedMesh v = validate(*m);
      if (v.mesh.faceCount() != m->triangleCount()) std::abort();
    });
    Timing ti = median(repeats, [&] {
      MeshInfo i = meshInfo(*m);
      if (i.euler != 0) std::abort();
    });
    std::printf("%-10s %9.3f (%6.3f) %9.3f (%6.3f) %9.3f (%6.3f)\n", m == &grid ? "generated" : "shuffled", tb.wall,
                tb.cpu, tv.wall, tv.cpu, ti.wall, ti.cpu);
  }
  return 0;
}
