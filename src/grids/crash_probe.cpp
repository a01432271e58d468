#include "grids/crash_probe.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <exception>
#include <fstream>

namespace caligo {
namespace {

constexpr size_t kMaxMessage = 2000;

// The process's current virtual size (first field of /proc/self/statm, in pages).
uint64_t address_space_bytes() {
  std::ifstream statm("/proc/self/statm");
  uint64_t pages = 0;
  statm >> pages;
  return pages * uint64_t(::sysconf(_SC_PAGESIZE));
}

[[noreturn]] void child(int out, const std::function<void()>& body, uint64_t address_space_limit) {
  if (address_space_limit > 0) {
    const rlimit limit{address_space_limit, address_space_limit};
    ::setrlimit(RLIMIT_AS, &limit);
  }
  std::string message;
  try {
    body();
    ::_exit(0);
  } catch (const std::exception& e) {
    message = e.what();
  } catch (...) {
    message = "unknown exception";
  }
  message.resize(std::min(message.size(), kMaxMessage));
  [[maybe_unused]] const ssize_t n = ::write(out, message.data(), message.size());
  ::_exit(1);
}

// Reads until the child closes the pipe (it exits or dies), or the deadline passes.
bool drain(int in, std::string& message, std::chrono::steady_clock::time_point deadline) {
  char buffer[512];
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    pollfd p{in, POLLIN, 0};
    const int ready = ::poll(&p, 1, int(left.count()));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) return false;
    const ssize_t n = ::read(in, buffer, sizeof(buffer));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return true;  // end of file: the child is gone
    if (message.size() < kMaxMessage) message.append(buffer, size_t(n));
  }
}

}  // namespace

ProbeOutcome probe_in_child(const std::function<void()>& body, std::chrono::milliseconds timeout,
                            uint64_t memory_allowance) {
  const uint64_t address_space_limit = memory_allowance > 0 ? address_space_bytes() + memory_allowance : 0;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) return {ProbeResult::kUnknown, ""};
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    return {ProbeResult::kUnknown, ""};
  }
  if (pid == 0) {
    ::close(fds[0]);
    child(fds[1], body, address_space_limit);
  }
  ::close(fds[1]);
  std::string message;
  const bool ended = drain(fds[0], message, deadline);
  ::close(fds[0]);
  int status = 0;
  if (!ended) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    return {ProbeResult::kUnknown, ""};
  }
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return {ProbeResult::kUnknown, ""};
  if (WIFSIGNALED(status)) return {ProbeResult::kCrashed, ""};
  if (WEXITSTATUS(status) == 0) return {ProbeResult::kSurvived, ""};
  return {ProbeResult::kThrew, message};
}

}  // namespace caligo
