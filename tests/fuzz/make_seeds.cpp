// Writes the libFuzzer seed corpora: small valid meshes in every format our readers take, from
// our writers and a few hand-written variants (comments, CRLF, polygons, negative OBJ indices,
// vt/vn, OFF header variants, PLY extra properties and list types, big-endian, float vertices,
// binary STL whose header starts with "solid").
//
//   make_seeds OUT_DIR      -> OUT_DIR/<target>/seed-*  for targets auto obj off stl-ascii
//                              stl-binary ply-ascii ply-le ply-be
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <sys/stat.h>
#include <vector>

#include "mesh/mesh_io.h"

using namespace conformesh;

namespace {

std::string outDir;
int counter = 0;

void put(const std::string& target, const std::vector<uint8_t>& bytes) {
  for (const std::string& t : {target, std::string("auto")}) {
    std::string dir = outDir + "/" + t;
    mkdir(dir.c_str(), 0755);
    std::ofstream(dir + "/seed-" + std::to_string(counter), std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  }
  ++counter;
}
void put(const std::string& target, const std::string& text) { put(target, std::vector<uint8_t>(text.begin(), text.end())); }

MeshBuffers tetra() {
  MeshBuffers m;
  m.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  m.triangles = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  return m;
}

MeshBuffers gridWithUvs(int n) {
  MeshBuffers m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      m.positions.insert(m.positions.end(), {i * 0.5, j * 0.25, 0.125 * i * j - 1e-3});
      m.uvs.insert(m.uvs.end(), {double(i) / n, double(j) / n});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n) + 2, d = a + uint32_t(n) + 1;
      m.triangles.insert(m.triangles.end(), {a, b, c, a, c, d});
    }
  return m;
}

template <class T>
void pushBinary(std::vector<uint8_t>& out, T v, bool bigEndian) {
  uint8_t b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (bigEndian)
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  out.insert(out.end(), b, b + sizeof(T));
}

//! Binary PLY with float vertices, an extra uchar property and a uchar/uint face list (or
//! int/int when `intCount`), plus an extra face property.
std::vector<uint8_t> plyFloat(bool bigEndian, bool intCount) {
  std::string h = std::string("ply\nformat ") + (bigEndian ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\ncomment seed\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                  "property uchar quality\nelement face 2\nproperty list " +
                  (intCount ? "int int" : "uchar uint") + " vertex_indices\nproperty short tag\nend_header\n";
  std::vector<uint8_t> out(h.begin(), h.end());
  float p[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0.5f}};
  for (auto& v : p) {
    for (float x : v) pushBinary(out, x, bigEndian);
    out.push_back(7);
  }
  for (int f = 0; f < 2; ++f) {
    if (intCount) pushBinary<int32_t>(out, f == 0 ? 3 : 4, bigEndian);
    else out.push_back(f == 0 ? 3 : 4);
    uint32_t idx[4] = {0, 1, 2, 3};
    for (int k = 0; k < (f == 0 ? 3 : 4); ++k) {
      if (intCount) pushBinary<int32_t>(out, int32_t(idx[k]), bigEndian);
      else pushBinary<uint32_t>(out, idx[k], bigEndian);
    }
    pushBinary<int16_t>(out, int16_t(-f), bigEndian);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_seeds OUT_DIR\n");
    return 2;
  }
  outDir = argv[1];
  mkdir(outDir.c_str(), 0755);
  const std::pair<const char*, MeshFormat> formats[] = {
      {"obj", MeshFormat::Obj},           {"off", MeshFormat::Off},         {"stl-ascii", MeshFormat::StlAscii},
      {"stl-binary", MeshFormat::StlBinary}, {"ply-ascii", MeshFormat::PlyAscii}, {"ply-le", MeshFormat::PlyBinaryLE},
      {"ply-be", MeshFormat::PlyBinaryBE}};
  for (const MeshBuffers& m : {tetra(), gridWithUvs(2)})
    for (auto& f : formats) put(f.first, writeMesh(m, f.second));

  // OBJ variants
  put("obj", std::string("# comment\nmtllib a.mtl\no thing\nv 0 0 0\nv 1 0 0 1.0\nv 1 1 0\nv 0 1 0\n"
                         "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\ng g1\nusemtl m\ns off\n"
                         "f 1/1/1 2/2/1 3/3/1 4/4/1\nf -4//1 -2//1 -1//1\nl 1 2\n"));
  put("obj", std::string("v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nv 1e3 -2.5E-3 +7\r\nf 1 2 3\r\nf 2 4 3\r\n"));
  put("obj", std::string("v 0.5 0.5 0.5 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1/1 2/2 3/3\nvt 0 0\nvt 1 0\nvt 0 1\n"));
  // OFF variants
  put("off", std::string("OFF\n# comment\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n3 0 2 3 255 0 0\n"));
  put("off", std::string("OFF 3 1 0\n0 0 0 1 0 0 0 1 0\n3 0 1 2\n"));
  put("off", std::string("COFF\n3 1 3\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n3 0 1 2\n"));
  put("off", std::string("NOFF\n\n  3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 2 1 0\n"));
  // PLY variants
  put("ply-ascii", std::string("ply\nformat ascii 1.0\ncomment c\nelement vertex 4\nproperty double x\n"
                               "property double y\nproperty double z\nproperty uchar red\nelement face 2\n"
                               "property list uchar int vertex_indices\nproperty int flags\nend_header\n"
                               "0 0 0 255\n1 0 0 0\n1 1 0 9\n0 1 0 1\n3 0 1 2 7\n4 0 1 2 3 -1\n"));
  put("ply-le", plyFloat(false, false));
  put("ply-le", plyFloat(false, true));
  put("ply-be", plyFloat(true, false));
  put("ply-be", plyFloat(true, true));
  // STL: ascii with odd spacing; binary whose 80-byte header starts with "solid"
  put("stl-ascii", std::string("solid s\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n"
                               "   vertex 0 1 0\n  endloop\n endfacet\nendsolid s\n"));
  {
    std::vector<uint8_t> b = writeMesh(tetra(), MeshFormat::StlBinary);
    std::memcpy(b.data(), "solid binary-but-says-solid", 27);
    put("stl-binary", b);
  }
  std::printf("make_seeds: %d seeds in %s\n", counter, outDir.c_str());
  return 0;
}
