#include "interrupt.h"

#include <unistd.h>

#include <csignal>
#include <ctime>
#include <cstring>

namespace caligo {
namespace {

std::atomic<bool> g_stop{false};
volatile std::sig_atomic_t g_signal = 0;
struct sigaction g_previous_int, g_previous_term;

volatile std::sig_atomic_t g_first_ms = 0;  // CLOCK_MONOTONIC of the first signal, ms (wraps harmlessly)

long monotonic_ms() {
  timespec now{};
  ::clock_gettime(CLOCK_MONOTONIC, &now);  // async-signal-safe
  return long(now.tv_sec) * 1000 + now.tv_nsec / 1'000'000;
}

// Async-signal-safe: an atomic store, or write(2) and _exit(2) for the second signal. A repeat
// within half a second is the same request delivered twice (GNU timeout and some supervisors
// signal the process and then its whole group), not a second Ctrl-C.
void on_signal(int sig) {
  if (g_signal != 0) {
    if (unsigned(std::sig_atomic_t(monotonic_ms())) - unsigned(g_first_ms) < 500u) return;
    constexpr char kMessage[] = "\ncaligo: second interrupt: quitting without saving\n";
    [[maybe_unused]] const ssize_t ignored = ::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
    ::_exit(128 + sig);
  }
  g_signal = sig;
  g_first_ms = std::sig_atomic_t(monotonic_ms());
  g_stop.store(true);
  constexpr char kMessage[] = "\ncaligo: interrupted: finishing the pixels in flight and saving (again to quit)\n";
  [[maybe_unused]] const ssize_t ignored = ::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
}

}  // namespace

static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

InterruptGuard::InterruptGuard() {
  g_stop.store(false);
  g_signal = 0;
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &g_previous_int);
  sigaction(SIGTERM, &action, &g_previous_term);
}

InterruptGuard::~InterruptGuard() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
}

const std::atomic<bool>& InterruptGuard::stop() const { return g_stop; }
int InterruptGuard::signal_number() const { return int(g_signal); }

void InterruptGuard::request_stop() const {
  if (g_signal == 0) {
    g_signal = SIGINT;
    g_first_ms = std::sig_atomic_t(monotonic_ms());
  }
  g_stop.store(true);
}

}  // namespace caligo
