// conformesh — native command-line interface.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>
#if defined(__GLIBC__)
#include <gnu/libc-version.h>
#include <malloc.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
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
  std::fprintf(out, "\n  conformesh COMMAND --help   flags, defaults and units of a command\n"
                    "  conformesh --version        print the version\n");
}

#if defined(__GLIBC__) && defined(__linux__)
// Transparent huge pages for the heap. Where the kernel gives them only to memory that asks
// (THP "madvise", the default of many distributions and VMs), every 4 KiB page a run touches
// first costs a fault, plus the TLB misses of 4 KiB pages (docs/decisions/0014). glibc >= 2.35 asks for huge pages for its heap
// when started with the tunable glibc.malloc.hugetlb=1, which is read only at process start:
// the CLI starts itself again once with it. Skipped when the user set GLIBC_TUNABLES (theirs
// win), under valgrind (its tools would lose the child), when CONFORMESH_NO_REEXEC is set, and
// where it cannot matter (THP "always" or "never", older glibc). A failed exec carries on.
void reexecWithHugePages(char** argv) {
  if (std::getenv("GLIBC_TUNABLES") || std::getenv("CONFORMESH_NO_REEXEC")) return;
  if (const char* pre = std::getenv("LD_PRELOAD"); pre && std::strstr(pre, "vgpreload")) return;
  int major = 0, minor = 0;
  if (std::sscanf(gnu_get_libc_version(), "%d.%d", &major, &minor) != 2 || major * 100 + minor < 235) return;
  // started through the dynamic loader (`ld.so ./conformesh …`): /proc/self/exe is the loader,
  // which would take the first argument for the program to run
  char exe[4096];
  const ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (len <= 0) return;
  exe[len] = 0;
  const char* base = std::strrchr(exe, '/');
  if (std::strncmp(base ? base + 1 : exe, "ld-", 3) == 0 || std::strncmp(base ? base + 1 : exe, "ld.so", 5) == 0) return;
  std::ifstream thp("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string mode;
  if (!std::getline(thp, mode) || mode.find("[madvise]") == std::string::npos) return;
  if (setenv("CONFORMESH_NO_REEXEC", "1", 1) != 0 || setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1", 1) != 0) return;
  execv("/proc/self/exe", argv);
  unsetenv("GLIBC_TUNABLES");  // exec failed: go on as we are
}
#endif
}  // namespace

int main(int argc, char** argv) {
#if defined(__GLIBC__) && defined(__linux__)
  reexecWithHugePages(argv);
#endif
#if defined(__GLIBC__)
  // A run allocates and frees many large buffers (per patch, per stage). glibc maps each one
  // above its mmap threshold afresh and returns freed heap tops to the system, so every reuse
  // pays the page faults again. Keep freed memory in the
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
  if (name == "--version") {
    std::printf("conformesh %s\n", CONFORMESH_VERSION);
    return 0;
  }
  for (const auto& c : conformesh::cli::commandRegistry()) {
    if (name != c.name) continue;
    const std::vector<std::string> args(argv + 2, argv + argc);
    if (conformesh::cli::asksForHelp(args, c.flags())) {
      std::fputs(conformesh::cli::helpText(c.usage, c.summary, c.flags()).c_str(), stdout);
      return 0;
    }
    return c.run(args);
  }
  std::fprintf(stderr, "conformesh: unknown command '%s'\n\n", name.c_str());
  printUsage(stderr);
  return 2;
}
