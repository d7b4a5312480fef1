// Kill tests: a child process repeats a write for ever and is killed with SIGKILL
// after a varying delay, many times over, so that the kill lands at every point of
// the write (before it, inside the temporary file, between the rename and the folder's
// flush, after it). The caller checks the files after each kill.
#pragma once

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <functional>
#include <thread>

namespace imagepro::test {

// Forks a child that calls `write(i)` for i = 0, 1, 2 ... until it is killed, lets it
// run for `run_for`, then kills it with SIGKILL and reaps it. Returns false when the
// child ended by itself (a write failed: the child exits with status 1 then).
inline bool runThenKill(const std::function<bool(long)>& write, std::chrono::microseconds run_for) {
  const pid_t child = ::fork();
  if (child < 0) return false;
  if (child == 0) {
    for (long i = 0;; ++i)
      if (!write(i)) ::_exit(1);
  }
  std::this_thread::sleep_for(run_for);
  ::kill(child, SIGKILL);
  int status = 0;
  ::waitpid(child, &status, 0);
  return WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
}

// The delay of kill `k` of `kills`: spread over 0.2 .. 20 ms, then a few longer runs,
// with a little jitter so the kills do not fall in step with the writes.
inline std::chrono::microseconds killDelay(int k, int kills) {
  const long base = 200 + static_cast<long>(k) * 19800 / (kills > 1 ? kills - 1 : 1);
  return std::chrono::microseconds(base + std::rand() % 500);
}

}  // namespace imagepro::test
