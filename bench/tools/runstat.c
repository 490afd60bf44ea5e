/* Run a command and report its wall time and peak resident memory, the same way for every tool.
 *
 *   runstat STATS.json [--timeout SECONDS] -- COMMAND [ARGS...]
 *
 * The command's stdout and stderr pass through. STATS.json receives
 *   {"exitCode":N,"signal":S,"timedOut":bool,"wallSeconds":T,"userSeconds":U,"systemSeconds":Y,
 *    "peakRssBytes":B}
 * (peak RSS from wait4's rusage: the largest resident set of the child). Exit code: the child's,
 * 124 on timeout, 125 when the command could not be started. */
#define _GNU_SOURCE
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static volatile sig_atomic_t timed_out = 0;
static pid_t child = 0;
static void on_alarm(int sig) {
  (void)sig;
  timed_out = 1;
  if (child > 0) kill(-child, SIGKILL);
}

int main(int argc, char** argv) {
  if (argc < 4) {
    fprintf(stderr, "usage: runstat STATS.json [--timeout SECONDS] -- COMMAND [ARGS...]\n");
    return 2;
  }
  const char* statsPath = argv[1];
  int i = 2;
  unsigned timeout = 0;
  if (strcmp(argv[i], "--timeout") == 0 && i + 1 < argc) {
    timeout = (unsigned)strtoul(argv[i + 1], NULL, 10);
    i += 2;
  }
  if (i >= argc || strcmp(argv[i], "--") != 0 || i + 1 >= argc) {
    fprintf(stderr, "runstat: expected -- COMMAND\n");
    return 2;
  }
  char** cmd = argv + i + 1;
  double t0 = now();
  child = fork();
  if (child < 0) return 125;
  if (child == 0) {
    setpgid(0, 0); /* own process group: a timeout kills the whole tree */
    execvp(cmd[0], cmd);
    fprintf(stderr, "runstat: cannot run %s: %s\n", cmd[0], strerror(errno));
    _exit(125);
  }
  setpgid(child, child);
  if (timeout > 0) {
    signal(SIGALRM, on_alarm);
    alarm(timeout);
  }
  int status = 0;
  struct rusage ru;
  memset(&ru, 0, sizeof ru);
  while (wait4(child, &status, 0, &ru) < 0) {
    if (errno != EINTR) return 125;
  }
  double wall = now() - t0;
  int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  int sig = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  FILE* f = fopen(statsPath, "w");
  if (f) {
    fprintf(f,
            "{\"exitCode\":%d,\"signal\":%d,\"timedOut\":%s,\"wallSeconds\":%.6f,\"userSeconds\":%.6f,"
            "\"systemSeconds\":%.6f,\"peakRssBytes\":%lld}\n",
            code, sig, timed_out ? "true" : "false", wall, ru.ru_utime.tv_sec + 1e-6 * ru.ru_utime.tv_usec,
            ru.ru_stime.tv_sec + 1e-6 * ru.ru_stime.tv_usec, (long long)ru.ru_maxrss * 1024);
    fclose(f);
  }
  return timed_out ? 124 : code;
}
