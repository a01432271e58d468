#include "render/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace caligo {

std::string format_duration(double seconds) {
  char buf[64];
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  if (seconds < 1.0) {
    std::snprintf(buf, sizeof buf, "%.0f ms", seconds * 1e3);
  } else if (seconds < 60.0) {
    std::snprintf(buf, sizeof buf, "%.1f s", seconds);
  } else {
    const long s = std::lround(seconds);
    std::snprintf(buf, sizeof buf, "%ldm %02lds", s / 60, s % 60);
  }
  return buf;
}

Progress::Progress(std::string label, uint64_t total_samples, Style style)
    : label_(std::move(label)),
      total_(std::max<uint64_t>(total_samples, 1)),
      style_(style),
      start_(std::chrono::steady_clock::now()) {
  if (style_ == Style::kAuto) style_ = isatty(STDERR_FILENO) ? Style::kBar : Style::kLog;
  if (style_ != Style::kQuiet) reporter_ = std::thread([this] { run(); });
}

Progress::~Progress() { finish(); }

void Progress::finish() {
  {
    std::lock_guard lock(mutex_);
    if (stopping_) return;
    stopping_ = true;
  }
  wake_.notify_all();
  if (reporter_.joinable()) reporter_.join();
  if (style_ != Style::kQuiet) print(true);
}

void Progress::run() {
  std::unique_lock lock(mutex_);
  const auto period =
      style_ == Style::kBar ? std::chrono::milliseconds(200) : std::chrono::milliseconds(1000);
  while (!wake_.wait_for(lock, period, [this] { return stopping_; })) print(false);
}

void Progress::print(bool final) {
  const uint64_t done = std::min(done_.load(std::memory_order_relaxed), total_);
  const double fraction = double(done) / double(total_);
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = elapsed > 0 ? double(done) / elapsed : 0.0;
  const double eta = rate > 0 ? double(total_ - done) / rate : NAN;
  if (style_ == Style::kBar) {
    constexpr int kWidth = 30;
    const int filled = int(fraction * kWidth);
    std::string bar(size_t(filled), '#');
    bar.resize(kWidth, '-');
    std::fprintf(stderr, "\r%s [%s] %5.1f%%  %.3g samples/s  ETA %s   ", label_.c_str(), bar.c_str(),
                 100.0 * fraction, rate, final ? "0 ms" : format_duration(eta).c_str());
    if (final) std::fputc('\n', stderr);
  } else {
    const int decile = int(fraction * 10.0);
    if (!final && decile <= last_logged_decile_) return;
    last_logged_decile_ = decile;
    std::fprintf(stderr, "%s: %.0f%% (%.3g samples/s, elapsed %s, ETA %s)\n", label_.c_str(),
                 100.0 * fraction, rate, format_duration(elapsed).c_str(),
                 final ? "0 ms" : format_duration(eta).c_str());
  }
  std::fflush(stderr);
}

}  // namespace caligo
