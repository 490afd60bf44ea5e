#include <doctest/doctest.h>

#include <set>
#include <string>

#include "core/status.h"

using namespace conformesh;

TEST_CASE("status table: names and values are unique, lookups agree") {
  std::set<int> values;
  std::set<std::string> names;
  for (int i = 0; i < codeCount(); ++i) {
    Code c = codeAt(i);
    CHECK(values.insert(int(c)).second);
    CHECK(names.insert(codeName(c)).second);
    CHECK(std::string(codeMeaning(c)).size() > 3);
  }
  CHECK(codeIsFatal(Code::NonManifoldEdge));
  CHECK_FALSE(codeIsFatal(Code::DegenerateFace));
  CHECK(std::string(codeName(static_cast<Code>(9999))) == "Unknown");
}

TEST_CASE("Error carries code, stage and message") {
  try {
    fail(Code::ParseError, Stage::Read, "line 3: bad vertex");
    FAIL("fail() returned");
  } catch (const Error& e) {
    CHECK(e.code() == Code::ParseError);
    CHECK(e.stage() == Stage::Read);
    CHECK(e.status().message == "line 3: bad vertex");
    CHECK(std::string(stageName(e.stage())) == "read");
  }
}
