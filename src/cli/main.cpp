// conformesh — native command-line interface.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "cli/command.h"

namespace conformesh::cli {
std::vector<Command>& commandRegistry() {
  static std::vector<Command> registry;
  return registry;
}
}  // namespace conformesh::cli

namespace {
void printUsage(std::FILE* out) {
  auto commands = conformesh::cli::commandRegistry();
  std::sort(commands.begin(), commands.end(),
            [](const auto& a, const auto& b) { return std::strcmp(a.name, b.name) < 0; });
  std::fprintf(out, "usage: conformesh COMMAND [ARGS]\n\ncommands:\n");
  for (const auto& c : commands) std::fprintf(out, "  conformesh %s\n      %s\n", c.usage, c.summary);
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    printUsage(stderr);
    return 2;
  }
  std::string name = argv[1];
  if (name == "--help" || name == "-h" || name == "help") {
    printUsage(stdout);
    return 0;
  }
  for (const auto& c : conformesh::cli::commandRegistry()) {
    if (name == c.name) return c.run(std::vector<std::string>(argv + 2, argv + argc));
  }
  std::fprintf(stderr, "conformesh: unknown command '%s'\n\n", name.c_str());
  printUsage(stderr);
  return 2;
}
