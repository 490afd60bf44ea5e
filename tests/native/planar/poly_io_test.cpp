#include <doctest/doctest.h>

#include <string>

#include "planar/poly_io.h"
#include "planar_test_util.h"

using namespace planar_test;

namespace {
std::vector<uint8_t> bytes(const std::string& s) { return std::vector<uint8_t>(s.begin(), s.end()); }
Status parseStatus(const std::string& s) {
  try {
    readPoly(bytes(s));
  } catch (const Error& e) {
    return e.status();
  }
  return Status{};
}
}  // namespace

TEST_CASE(".poly: data files, comments, markers, attributes, 0-based numbering") {
  Pslg sq = loadPoly("square_holes");
  CHECK(sq.points.size() == 2 * 304);
  CHECK(sq.segments.size() == 2 * 304);
  CHECK(sq.holes.size() == 2 * 5);
  std::string text =
      "# a square\n"
      "4 2 1 1  # vertices with one attribute and a marker\n"
      "0 0 0 7.5 1\n1 1 0 7.5 1\n\n2 1 1 7.5 1\n3 0 1 7.5 1\n"
      "4 1\n0 0 1 5\n1 1 2 5\n2 2 3 6\n3 3 0 6\n"
      "1\n0 0.5 0.5\n";
  Pslg p = readPoly(bytes(text));
  CHECK(p.points == std::vector<double>{0, 0, 1, 0, 1, 1, 0, 1});
  CHECK(p.segments == std::vector<uint32_t>{0, 1, 1, 2, 2, 3, 3, 0});
  CHECK(p.segmentMarkers == std::vector<int32_t>{5, 5, 6, 6});
  CHECK(p.holes == std::vector<double>{0.5, 0.5});
  // write and read back
  std::string w = writePoly(p);
  Pslg q = readPoly(bytes(w));
  CHECK(q.points == p.points);
  CHECK(q.segments == p.segments);
  CHECK(q.segmentMarkers == p.segmentMarkers);
  CHECK(q.holes == p.holes);
}

TEST_CASE(".poly: errors name the line") {
  Status s = parseStatus("3 2 0 0\n1 0 0\n2 1 x\n3 0 1\n0 0\n");
  CHECK(s.code == Code::ParseError);
  CHECK(s.message.find("line 3") != std::string::npos);
  CHECK(parseStatus("3 2 0 0\n1 0 0\n2 1 0\n").code == Code::ParseError);           // truncated
  CHECK(parseStatus("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n1 0\n1 1 4\n").code == Code::IndexOutOfRange);
  CHECK(parseStatus("3 3 0 0\n").code == Code::ParseError);                          // 3D
  CHECK(parseStatus("0 2 0 0\n").code == Code::ParseError);                          // .node file
  CHECK(parseStatus("3 2 0 0\n1 0 0\n3 1 0\n2 0 1\n0 0\n").code == Code::ParseError);  // numbering
  CHECK(parseStatus("").code == Code::ParseError);
  CHECK(parseStatus("2 2 0 0\n1 0 nan\n2 1 0\n").code == Code::NonFiniteCoordinate);
}
