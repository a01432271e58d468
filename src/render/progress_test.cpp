// The progress reporter: durations formatted for people, and the final line of each style
// (stderr captured by gtest).
#include "render/progress.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/parallel.h"

namespace caligo {
namespace {

TEST(FormatDuration, MillisecondsSecondsAndMinutes) {
  EXPECT_EQ(format_duration(0.85), "850 ms");
  EXPECT_EQ(format_duration(0.0), "0 ms");
  EXPECT_EQ(format_duration(4.2), "4.2 s");
  EXPECT_EQ(format_duration(83.0), "1m 23s");
  EXPECT_EQ(format_duration(3600.0), "60m 00s");
  EXPECT_EQ(format_duration(std::nan("")), "?");
  EXPECT_EQ(format_duration(-1.0), "?");
  EXPECT_EQ(format_duration(INFINITY), "?");
}

TEST(Progress, QuietPrintsNothing) {
  ::testing::internal::CaptureStderr();
  {
    Progress p("render", 100, Progress::Style::kQuiet);
    p.advance(100);
  }
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

// Samples advanced from many threads all count; the final line says 100 % once, even when
// finish() is called before the destructor.
TEST(Progress, LogEndsWithOneFullLine) {
  ::testing::internal::CaptureStderr();
  {
    Progress p("render", 1000, Progress::Style::kLog);
    parallel_for(1000, [&](int) { p.advance(1); });
    p.finish();
  }
  const std::string err = ::testing::internal::GetCapturedStderr();
  const size_t full = err.find("render: 100%");
  ASSERT_NE(full, std::string::npos) << err;
  EXPECT_EQ(err.find("render: 100%", full + 1), std::string::npos) << err;
  EXPECT_NE(err.find("ETA 0 ms)\n", full), std::string::npos) << err;
}

TEST(Progress, BarIsFullAtTheEndAndEndsTheLine) {
  ::testing::internal::CaptureStderr();
  {
    Progress p("render", 10, Progress::Style::kBar);
    p.advance(4);
    p.advance(6);
  }
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("[" + std::string(30, '#') + "] 100.0%"), std::string::npos) << err;
  ASSERT_FALSE(err.empty());
  EXPECT_EQ(err.back(), '\n');
}

// More samples reported than announced (a render that overshoots) still prints 100 %.
TEST(Progress, OvershootIsClampedToTheTotal) {
  ::testing::internal::CaptureStderr();
  {
    Progress p("render", 10, Progress::Style::kLog);
    p.advance(25);
  }
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("render: 100%"), std::string::npos) << err;
  EXPECT_EQ(err.find("250%"), std::string::npos) << err;
}

}  // namespace
}  // namespace caligo
