// SIGINT and SIGTERM during a render: the first asks the render to stop (it finishes the pixels
// in flight, saves a checkpoint and a partial image, and says so); a second quits at once
// (one within half a second of the first is taken as the same request delivered twice).
#pragma once

#include <atomic>

namespace caligo {

class InterruptGuard {
 public:
  InterruptGuard();  // installs the handlers (one guard at a time)
  ~InterruptGuard();  // restores the previous ones
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

  // Becomes true at the first signal; render_up_to polls it between pixels.
  const std::atomic<bool>& stop() const;
  bool stopped() const { return stop().load(); }
  int signal_number() const;  // the first signal's number (0 before any)
  // A stop asked for by other means than a signal (the preview page's button): as a first SIGINT.
  void request_stop() const;
};

}  // namespace caligo
