#include "core/frame_pattern.h"

#include <gtest/gtest.h>

namespace caligo {
namespace {

TEST(FramePattern, SubstitutesPlainAndPaddedNumbers) {
  std::string error;
  EXPECT_EQ(substitute_frame("smoke_{frame}.vdb", 7, &error), "smoke_7.vdb");
  EXPECT_EQ(substitute_frame("smoke_{frame:4}.vdb", 7, &error), "smoke_0007.vdb");
  EXPECT_EQ(substitute_frame("{frame:04}/{frame:2}", 123, &error), "0123/123");
  EXPECT_EQ(substitute_frame("plain.vdb", 7, &error), "plain.vdb");
  EXPECT_TRUE(has_frame_pattern("a{frame:3}"));
  EXPECT_FALSE(has_frame_pattern("a{fram}"));
}

TEST(FramePattern, MalformedPatternsAreNamed) {
  std::string error;
  EXPECT_FALSE(substitute_frame("a_{frame:x}.vdb", 1, &error));
  EXPECT_NE(error.find("{frame:x}"), std::string::npos);
  EXPECT_FALSE(substitute_frame("a_{frame:10}.vdb", 1, &error));
  EXPECT_FALSE(substitute_frame("a_{frame.vdb", 1, &error));
  EXPECT_NE(error.find("not closed"), std::string::npos);
}

}  // namespace
}  // namespace caligo
