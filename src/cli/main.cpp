// conformesh — native command-line interface.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

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
#if defined(__GLIBC__)
  // A run allocates and frees many large buffers (per patch, per stage). glibc maps each one
  // above its mmap threshold afresh and returns freed heap tops to the system, so every reuse
  // pays the page faults again (on fandisk 0.004 a third of them). Keep freed memory in the
  // heap for the process's life instead: a command runs once and exits.
  mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
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
