// The shares of a frame among MPI ranks, without MPI: each sample and each row of the crop window
// goes to exactly one rank, in contiguous rank-ordered ranges of sizes differing by at most one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "distributed/frame.h"
#include "distributed/share.h"

namespace caligo::distributed {
namespace {

TEST(ShareOf, EverySampleExactlyOnceInContiguousBalancedRanges) {
  for (int ranks = 1; ranks <= 7; ++ranks)
    for (int spp = 1; spp <= 20; ++spp)
      for (int first : {0, 13}) {
        std::vector<int> seen(size_t(spp), 0);
        int next = first, smallest = spp, largest = 0;
        for (int r = 0; r < ranks; ++r) {
          const Range share = share_of(spp, first, r, ranks);
          ASSERT_GE(share.count, 0);
          EXPECT_EQ(share.first, next) << "rank " << r << " of " << ranks << ", spp " << spp;
          next = share.first + share.count;
          smallest = std::min(smallest, share.count);
          largest = std::max(largest, share.count);
          for (int s = share.first; s < share.first + share.count; ++s) ++seen[size_t(s - first)];
        }
        EXPECT_EQ(next, first + spp);
        EXPECT_LE(largest - smallest, 1) << ranks << " ranks, spp " << spp;
        for (int s = 0; s < spp; ++s) EXPECT_EQ(seen[size_t(s)], 1) << "sample " << s;
      }
}

TEST(ShareOf, RejectsBadRanks) {
  EXPECT_THROW(share_of(4, 0, 2, 2), std::invalid_argument);
  EXPECT_THROW(share_of(4, 0, -1, 2), std::invalid_argument);
  EXPECT_THROW(share_of(4, 0, 0, 0), std::invalid_argument);
  EXPECT_THROW(share_of(-1, 0, 0, 1), std::invalid_argument);
}

TEST(RowFraction, CropWindowsAtTheFractionsHoldExactlyThoseRows) {
  for (int height : {1, 2, 3, 7, 10, 33, 480, 1080, 4097, 65536})
    for (int row = 0; row <= height; row += std::max(1, height / 97)) {
      const float f = row_fraction(row, height);
      EXPECT_EQ(int(std::ceil(double(height) * double(f))), row) << row << " of " << height;
    }
}

// The row split through settings_for_rank: every pixel of the crop window in one rank's crop.
TEST(SettingsForRank, RowBandsTileTheCropWindowAndKeepTheSamples) {
  RenderSettings frame;
  frame.resolution = {37, 29};
  frame.spp = 5;
  frame.first_sample = 3;
  for (const CropWindow crop : {CropWindow{}, CropWindow{0.1f, 0.8f, 0.33f, 0.71f}})
    for (int ranks = 1; ranks <= 7; ++ranks) {
      frame.crop = crop;
      const PixelBounds all = crop.pixels(frame.resolution);
      std::vector<int> seen(size_t(frame.resolution.x * frame.resolution.y), 0);
      for (int r = 0; r < ranks; ++r) {
        const RenderSettings s = settings_for_rank(frame, Split::kRows, r, ranks);
        EXPECT_EQ(s.spp, frame.spp);
        EXPECT_EQ(s.first_sample, frame.first_sample);
        const PixelBounds b = s.crop.pixels(s.resolution);
        EXPECT_EQ(b.min.x, all.min.x);
        EXPECT_EQ(b.max.x, all.max.x);
        for (int y = b.min.y; y < b.max.y; ++y)
          for (int x = b.min.x; x < b.max.x; ++x) ++seen[size_t(y * frame.resolution.x + x)];
      }
      for (int y = 0; y < frame.resolution.y; ++y)
        for (int x = 0; x < frame.resolution.x; ++x) {
          const bool inside = x >= all.min.x && x < all.max.x && y >= all.min.y && y < all.max.y;
          EXPECT_EQ(seen[size_t(y * frame.resolution.x + x)], inside ? 1 : 0) << x << "," << y << ", " << ranks;
        }
    }
}

TEST(SettingsForRank, SampleSplitKeepsTheCropAndSplitsTheRange) {
  RenderSettings frame;
  frame.spp = 10;
  frame.first_sample = 4;
  const RenderSettings a = settings_for_rank(frame, Split::kSamples, 0, 3);
  const RenderSettings c = settings_for_rank(frame, Split::kSamples, 2, 3);
  EXPECT_EQ(a.first_sample, 4);
  EXPECT_EQ(a.spp, 4);
  EXPECT_EQ(c.first_sample, 11);
  EXPECT_EQ(c.spp, 3);
  EXPECT_TRUE(c.crop.full());
}

TEST(SplitFromName, KnowsSamplesAndRows) {
  EXPECT_EQ(split_from_name("samples"), Split::kSamples);
  EXPECT_EQ(split_from_name("rows"), Split::kRows);
  EXPECT_EQ(split_from_name("tiles"), std::nullopt);
}

TEST(LauncherWorldSize, ReadsOpenMpiAndPmixVariables) {
  ::unsetenv("OMPI_COMM_WORLD_SIZE");
  ::unsetenv("PMI_SIZE");
  ::unsetenv("PMIX_RANK");
  EXPECT_EQ(launcher_world_size(), std::nullopt);
  ::setenv("OMPI_COMM_WORLD_SIZE", "4", 1);
  EXPECT_EQ(launcher_world_size(), 4);
  ::setenv("OMPI_COMM_WORLD_SIZE", "4x", 1);
  EXPECT_EQ(launcher_world_size(), std::nullopt);
  ::unsetenv("OMPI_COMM_WORLD_SIZE");
  ::setenv("PMIX_RANK", "0", 1);
  ::setenv("SLURM_STEP_NUM_TASKS", "3", 1);
  EXPECT_EQ(launcher_world_size(), 3);
  ::unsetenv("PMIX_RANK");
  ::unsetenv("SLURM_STEP_NUM_TASKS");
}

}  // namespace
}  // namespace caligo::distributed
