// The progressive scheduler without the command line: passes end where one render of the same
// sample count would (bit for bit), checkpoints come between passes and their failures do not
// end the render, and the error target and the stop request end it early.
#include "render/progressive.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <vector>

#include "scene/builtins.h"
#include "scene/scene.h"

namespace caligo {
namespace {

struct Fixture {
  std::unique_ptr<Scene> scene = Scene::build(parse_builtin(*find_builtin("lamp-in-fog")));
  RenderSettings settings = [] {
    RenderSettings s;
    s.resolution = {12, 9};
    s.spp = 9;
    s.seed = 3;
    return s;
  }();
};

TEST(Progressive, PassesEndWhereOneRenderWould) {
  const Fixture f;
  Film once(f.settings.resolution, f.settings.aovs);
  render_up_to(once, *f.scene, f.settings, f.settings.spp);
  Film passes(f.settings.resolution, f.settings.aovs);
  std::vector<int> done;
  ProgressiveHooks hooks;
  hooks.on_pass = [&](int d, int target, double) {
    EXPECT_EQ(target, 9);
    done.push_back(d);
  };
  ProgressiveSchedule schedule;
  schedule.time_limit = 1e6;  // passes, but never the limit
  const ProgressiveResult r = render_progressive(passes, *f.scene, f.settings, schedule, hooks);
  EXPECT_TRUE(r.stopped_by.empty());
  EXPECT_TRUE(passes == once);
  // 1 sample first, then doubling: 1, 2, 4, 8, 9.
  EXPECT_EQ(done, (std::vector<int>{1, 2, 4, 8, 9}));
  EXPECT_EQ(r.stats.paths, uint64_t(12 * 9 * 9));
  EXPECT_EQ(sample_range(passes, f.settings), std::make_pair(9, 9));
}

// caligo render's default: refinement alone gives the same passes and the same film, and a stop
// after any pass leaves every pixel with that pass's samples (a whole picture, not tiles).
TEST(Progressive, RefinementIsAWholePictureAtEveryPass) {
  const Fixture f;
  Film once(f.settings.resolution, f.settings.aovs);
  render_up_to(once, *f.scene, f.settings, f.settings.spp);
  ProgressiveSchedule schedule;
  schedule.refine = true;
  Film refined(f.settings.resolution, f.settings.aovs);
  std::vector<int> done;
  ProgressiveHooks hooks;
  hooks.on_pass = [&](int d, int, double) { done.push_back(d); };
  render_progressive(refined, *f.scene, f.settings, schedule, hooks);
  EXPECT_TRUE(refined == once);
  EXPECT_EQ(done, (std::vector<int>{1, 2, 4, 8, 9}));
  std::atomic<bool> stop{false};
  hooks.on_pass = [&](int d, int, double) {
    if (d == 2) stop = true;  // as a Ctrl-C between the second and third passes
  };
  Film stopped(f.settings.resolution, f.settings.aovs);
  render_progressive(stopped, *f.scene, f.settings, schedule, hooks, &stop);
  EXPECT_EQ(sample_range(stopped, f.settings), std::make_pair(2, 2));
}

// A resumed film continues from its own count; a failing checkpoint is reported and the
// render goes on to the target.
TEST(Progressive, ResumesAndSurvivesFailedCheckpoints) {
  const Fixture f;
  Film film(f.settings.resolution, f.settings.aovs);
  render_up_to(film, *f.scene, f.settings, 3);
  int saves = 0, failures = 0;
  ProgressiveHooks hooks;
  hooks.save_checkpoint = [&](const Film&) {
    ++saves;
    throw std::runtime_error("disk full");
  };
  hooks.on_checkpoint_failed = [&](const std::exception& e) {
    EXPECT_STREQ(e.what(), "disk full");
    ++failures;
  };
  ProgressiveSchedule schedule;
  schedule.checkpoint_every = 0.0;  // after every pass but the last
  render_progressive(film, *f.scene, f.settings, schedule, hooks);
  Film once(f.settings.resolution, f.settings.aovs);
  render_up_to(once, *f.scene, f.settings, f.settings.spp);
  EXPECT_TRUE(film == once);
  EXPECT_EQ(saves, 5);  // after the passes to 4, 5, 6, 7 and 8 (one sample each), not after 9
  EXPECT_EQ(failures, saves);
}

TEST(Progressive, ErrorTargetAndStopEndEarly) {
  Fixture f;
  f.settings.aovs = f.settings.aovs.with(Aov::kVariance);
  Film film(f.settings.resolution, f.settings.aovs);
  ProgressiveSchedule schedule;
  schedule.target_rmse = 1e30;  // met by the first pass that can estimate it
  const ProgressiveResult r = render_progressive(film, *f.scene, f.settings, schedule, {});
  EXPECT_NE(r.stopped_by.find("the target RMSE"), std::string::npos) << r.stopped_by;
  EXPECT_LT(sample_range(film, f.settings).second, f.settings.spp);
  const std::atomic<bool> stop{true};
  Film untouched(f.settings.resolution, f.settings.aovs);
  schedule.target_rmse.reset();
  schedule.time_limit = 1e6;
  render_progressive(untouched, *f.scene, f.settings, schedule, {}, &stop);
  EXPECT_EQ(sample_range(untouched, f.settings), std::make_pair(0, 0));
}

// The time limit is a deadline: a first pass far longer than the limit (1 sample of a large
// frame, as a machine under load makes of any pass) is cut at it, not finished.
TEST(Progressive, TheTimeLimitCutsAPassThatRunsPastIt) {
  Fixture f;
  f.settings.resolution = {640, 480};
  f.settings.threads = 1;
  f.settings.spp = 64;
  Film once(f.settings.resolution, f.settings.aovs);
  const auto start = std::chrono::steady_clock::now();
  RenderSettings one = f.settings;
  one.spp = 1;
  render_up_to(once, *f.scene, one, 1);
  const double pass = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_GT(pass, 0.2) << "the 1-sample pass must outlast the limit below";
  Film film(f.settings.resolution, f.settings.aovs);
  ProgressiveSchedule schedule;
  schedule.time_limit = 0.02;
  const ProgressiveResult r = render_progressive(film, *f.scene, f.settings, schedule, {});
  EXPECT_NE(r.stopped_by.find("cut"), std::string::npos) << r.stopped_by;
  EXPECT_LT(r.stats.seconds, 0.5 * pass) << "the pass was finished, not cut";
  const auto [fewest, most] = sample_range(film, f.settings);
  EXPECT_EQ(fewest, 0);
  EXPECT_EQ(most, 1);
}

}  // namespace
}  // namespace caligo
