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

//! Parse args. `valueFlags` lists the flags that take a value (e.g. {"-o", "--min-angle"}),
//! `switches` those that do not; any other "-x" throws Error(InvalidArgument, "unknown option").
Args parseArgs(const std::vector<std::string>& args, const std::vector<std::string>& valueFlags,
               const std::vector<std::string>& switches);

//! One flag of a command: the one list its parsing and its --help both read.
struct Flag {
  std::string name;      //!< "--min-angle", "-o"
  std::string value;     //!< what its value is, as help shows it ("DEG"); empty for a switch
  std::string help;      //!< what it sets, with its units
  std::string fallback;  //!< its default as help shows it; empty when there is none to show
};

//! parseArgs with the value flags and switches of `flags`.
Args parseArgs(const std::vector<std::string>& args, const std::vector<Flag>& flags);

//! True when args hold --help or -h where a flag may stand (not as the value of a value flag).
bool asksForHelp(const std::vector<std::string>& args, const std::vector<Flag>& flags);

//! A command's --help: "usage: conformesh USAGE", the summary, then one line a flag.
std::string helpText(const std::string& usage, const std::string& summary, const std::vector<Flag>& flags);

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
//! The --boundary value that selects b ("circle", "free", "corners").
const char* boundaryFlagValue(conformal::BoundaryCondition b);

}  // namespace conformesh::cli
