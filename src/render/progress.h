// Progress of a long render on stderr: on a terminal, one bar redrawn in place with
// percentage, samples per second and ETA; otherwise a plain log line every 10 %.
// advance() is called from render threads; a reporter thread does all the printing.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

namespace caligo {

class Progress {
 public:
  enum class Style { kAuto, kBar, kLog, kQuiet };

  Progress(std::string label, uint64_t total_samples, Style style = Style::kAuto);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void advance(uint64_t samples) { done_.fetch_add(samples, std::memory_order_relaxed); }
  // Prints the final state and stops the reporter; called by the destructor if not before.
  void finish();

 private:
  void run();
  void print(bool final);

  std::string label_;
  uint64_t total_;
  Style style_;
  std::atomic<uint64_t> done_{0};
  std::chrono::steady_clock::time_point start_;
  int last_logged_decile_ = -1;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::thread reporter_;
};

// "1m 23s", "4.2 s", "850 ms"
std::string format_duration(double seconds);

}  // namespace caligo
