// conformesh CLI — command registry. Each command lives in its own cmd_<name>.cpp and
// registers itself with a static CommandRegistrar, so commands are added without editing main.
#pragma once

#include <string>
#include <vector>

#include "cli/cli_util.h"

namespace conformesh::cli {

using CommandFn = int (*)(const std::vector<std::string>& args);

struct Command {
  const char* name;
  const char* usage;    // one line: "info FILE [--json]"
  const char* summary;  // what it does
  std::vector<Flag> (*flags)();  // every flag it accepts: what its parsing and its --help read
  CommandFn run;
};

std::vector<Command>& commandRegistry();

struct CommandRegistrar {
  explicit CommandRegistrar(Command c) { commandRegistry().push_back(c); }
};

}  // namespace conformesh::cli
