#include "grids/crash_probe.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <thread>

namespace caligo {

ProbeResult probe_in_child(const std::function<void()>& body, std::chrono::milliseconds timeout) {
  const pid_t pid = ::fork();
  if (pid < 0) return ProbeResult::kUnknown;
  if (pid == 0) {
    int code = 0;
    try {
      body();
    } catch (...) {
      code = 1;
    }
    ::_exit(code);
  }
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  auto pause = std::chrono::microseconds(100);
  for (;;) {
    int status = 0;
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) {
      if (WIFSIGNALED(status)) return ProbeResult::kCrashed;
      return WEXITSTATUS(status) == 0 ? ProbeResult::kSurvived : ProbeResult::kThrew;
    }
    if (done < 0) return ProbeResult::kUnknown;
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      return ProbeResult::kUnknown;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(20000));
  }
}

}  // namespace caligo
