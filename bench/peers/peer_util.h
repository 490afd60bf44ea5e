// Small helpers shared by the peer drivers (bench only, not part of the library): wall clock,
// peak resident memory, Triangle .poly reading, JSON output.
#pragma once

#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace peer {

inline double now() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

//! Peak resident set size of this process so far, in bytes (Linux reports ru_maxrss in KiB).
inline long long peakRssBytes() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return (long long)ru.ru_maxrss * 1024;
}

//! A planar straight-line graph in Triangle's .poly format (Shewchuk's Triangle documentation,
//! "The .poly file"): vertices (numbered from 0 or 1, as the first one), segments, hole points.
struct Poly {
  std::vector<double> xy;               // 2 per vertex
  std::vector<std::pair<int, int>> seg;  // 0-based vertex indices
  std::vector<double> holes;             // 2 per hole seed
};

namespace detail {
//! Next non-empty line with comments (#...) removed, split into tokens.
inline bool tokens(std::istream& in, std::vector<std::string>& out) {
  std::string line;
  while (std::getline(in, line)) {
    auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream ss(line);
    out.clear();
    std::string t;
    while (ss >> t) out.push_back(t);
    if (!out.empty()) return true;
  }
  return false;
}
}  // namespace detail

inline Poly readPoly(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  Poly p;
  std::vector<std::string> t;
  auto need = [&](size_t n, const char* what) {
    if (!detail::tokens(in, t) || t.size() < n) throw std::runtime_error(std::string("bad .poly: ") + what);
  };
  need(1, "vertex header");
  long nv = std::stol(t[0]);
  if (nv <= 0) throw std::runtime_error(".poly with vertices in a separate .node file is not supported");
  int base = -1;
  p.xy.resize(2 * size_t(nv));
  for (long i = 0; i < nv; ++i) {
    need(3, "vertex");
    long id = std::stol(t[0]);
    if (base < 0) base = int(id);
    long k = id - base;
    if (k < 0 || k >= nv) throw std::runtime_error("bad .poly: vertex number out of range");
    p.xy[2 * k] = std::stod(t[1]);
    p.xy[2 * k + 1] = std::stod(t[2]);
  }
  need(1, "segment header");
  long ns = std::stol(t[0]);
  for (long i = 0; i < ns; ++i) {
    need(3, "segment");
    int a = std::stoi(t[1]) - base, b = std::stoi(t[2]) - base;
    if (a < 0 || b < 0 || a >= nv || b >= nv) throw std::runtime_error("bad .poly: segment endpoint out of range");
    p.seg.emplace_back(a, b);
  }
  if (detail::tokens(in, t)) {
    long nh = std::stol(t[0]);
    for (long i = 0; i < nh; ++i) {
      need(3, "hole");
      p.holes.push_back(std::stod(t[1]));
      p.holes.push_back(std::stod(t[2]));
    }
  }
  return p;
}

//! JSON number (null when not finite).
inline std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

//! Value of "--name X" in argv, or fallback.
inline std::string arg(int argc, char** argv, const std::string& name, const std::string& fallback = "") {
  for (int i = 1; i + 1 < argc; ++i)
    if (name == argv[i]) return argv[i + 1];
  return fallback;
}

}  // namespace peer
