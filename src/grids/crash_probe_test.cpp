#include "grids/crash_probe.h"

#include <gtest/gtest.h>

#include <csignal>
#include <stdexcept>
#include <thread>
#include <vector>

namespace caligo {
namespace {

using namespace std::chrono_literals;

TEST(CrashProbe, ReportsSurvivalExceptionsCrashesAndHangs) {
  EXPECT_EQ(probe_in_child([] {}, 10s).result, ProbeResult::kSurvived);
  const ProbeOutcome threw = probe_in_child([] { throw std::runtime_error("bad chunk size"); }, 10s);
  EXPECT_EQ(threw.result, ProbeResult::kThrew);
  EXPECT_EQ(threw.message, "bad chunk size");
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer catches the signal itself and exits with an error code: not survived.
  EXPECT_NE(probe_in_child([] { std::raise(SIGSEGV); }, 10s).result, ProbeResult::kSurvived);
#else
  EXPECT_EQ(probe_in_child([] { std::raise(SIGSEGV); }, 10s).result, ProbeResult::kCrashed);
#endif
  EXPECT_EQ(probe_in_child([] { std::abort(); }, 10s).result, ProbeResult::kCrashed);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(probe_in_child([] { std::this_thread::sleep_for(60s); }, 200ms).result, ProbeResult::kUnknown);
  EXPECT_LT(std::chrono::steady_clock::now() - start, 5s);
  // A capped address space turns a huge allocation into an exception (AddressSanitizer's
  // allocator aborts instead of throwing, so under ASan the child counts as crashed).
  const ProbeOutcome big = probe_in_child(
      [] {
        std::vector<char> huge(size_t(8) << 30, 1);
        if (huge[12345] != 1) std::abort();
      },
      10s, uint64_t(256) << 20);
#if defined(__SANITIZE_ADDRESS__)
  EXPECT_NE(big.result, ProbeResult::kSurvived);
#else
  EXPECT_EQ(big.result, ProbeResult::kThrew);
  EXPECT_NE(big.message.find("alloc"), std::string::npos) << big.message;
#endif
  // The parent is unaffected by what the child did.
  int touched = 0;
  probe_in_child([&] { touched = 1; }, 10s);
  EXPECT_EQ(touched, 0);
}

}  // namespace
}  // namespace caligo
