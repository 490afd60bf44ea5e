// conformesh CLI — command registry. Each command lives in its own cmd_<name>.cpp and
// registers itself with a static CommandRegistrar, so commands are added without editing main.
#pragma once

#include <string>
#include <vector>

namespace conformesh::cli {

using CommandFn = int (*)(const std::vector<std::string>& args);

struct Command {
  const char* name;
  const char* usage;    // one line: "info FILE [--json]"
  const char* summary;  // what it does
  CommandFn run;
};

std::vector<Command>& commandRegistry();

struct CommandRegistrar {
  explicit CommandRegistrar(Command c) { commandRegistry().push_back(c); }
};

}  // namespace conformesh::cli
