#include <doctest/doctest.h>

#include <cctype>
#include <set>
#include <string>

#include "core/stages.h"

using namespace conformesh;

namespace {
// "curveMesh" -> "curve-mesh": the report name is the seconds key in words
std::string dashed(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (std::isupper(static_cast<unsigned char>(c))) out += '-';
    out += char(std::tolower(static_cast<unsigned char>(c)));
  }
  return out;
}
}  // namespace

TEST_CASE("stage table: unique names, keys and labels; the name is the key in words") {
  std::set<std::string> names, keys, labels;
  for (int i = 0; i < stageCount(); ++i) {
    const Stage s = Stage(i);
    CHECK(names.insert(stageName(s)).second);
    CHECK(keys.insert(stageKey(s)).second);
    CHECK(labels.insert(stageLabel(s)).second);
    CHECK(std::string(stageName(s)) == dashed(stageKey(s)));
    CHECK(stageWeight(s) >= 0);
    if (!isRemeshStage(s)) CHECK(stageWeight(s) == 0);
  }
  CHECK(std::string(stageName(Stage(stageCount()))) == "unknown");
}

TEST_CASE("stage table: remesh()'s stages are one run of rows, and their intervals tile [0, 1] in order") {
  int previous = -1;
  for (Stage s : kRemeshStages) {
    if (previous >= 0) CHECK(int(s) == previous + 1);
    previous = int(s);
  }
  double at = 0;
  for (int i = 0; i < stageCount(); ++i) {
    const StageInterval iv = progressInterval(Stage(i));
    CHECK(iv.lo == at);
    CHECK(iv.hi >= iv.lo);
    at = iv.hi;
  }
  CHECK(at == 1.0);
}
