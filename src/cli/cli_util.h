// conformesh CLI — small helpers shared by the commands: argument parsing, files, JSON output.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "conformal/ricci_flow.h"
#include "core/status.h"

namespace conformesh::cli {

//! Parsed command line: positional arguments, and flags "--name value" / "--name" (value "").
struct Args {
  std::vector<std::string> positional;
  std::vector<std::pair<std::string, std::string>> flags;

  bool has(const std::string& name) const;
  std::string get(const std::string& name, const std::string& fallback = "") const;
  //! Value of a numeric flag; throws Error(InvalidArgument) when it does not parse.
  double number(const std::string& name, double fallback) const;
};

//! Parse args. `valueFlags` lists the flags that take a value (e.g. {"-o", "--min-angle"});
//! any other "--x" is a switch. Unknown flags throw Error(InvalidArgument) when `known` is given.
Args parseArgs(const std::vector<std::string>& args, const std::vector<std::string>& valueFlags,
               const std::vector<std::string>& switches);

std::vector<uint8_t> readFileBytes(const std::string& path);  // throws Error(IoError)
void writeFileBytes(const std::string& path, const std::vector<uint8_t>& bytes);

//! JSON string literal with escapes.
std::string jsonString(const std::string& s);
//! A number for JSON (finite: shortest round-trip form; non-finite: null).
std::string jsonNumber(double v);

//! Report an error: as {"error":{"code":...,"name":...,"stage":...,"message":...}} on stdout when
//! json is true, else as a line on stderr. Returns the process exit code (1).
int reportError(const Status& s, bool json);

//! --boundary circle|free|corners (InvalidArgument otherwise); `fallback` when absent.
conformal::BoundaryCondition boundaryFlag(const Args& args, const char* fallback);

}  // namespace conformesh::cli
