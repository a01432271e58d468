// The production integrator against the reference ladder on the built-in volume scenes
// (at low resolution). `default` holds a dielectric, which the ladder does not handle, and
// `lamp-in-fog` puts a point light inside the medium, which gives the ladder's collision
// estimators unbounded variance; both are covered by the analytic and custom-scene tests.
#include <gtest/gtest.h>

#include "integrators/reference.h"
#include "render/render.h"
#include "scene/builtins.h"
#include "scene/scene_parser.h"

namespace caligo {
namespace {

struct Comparison {
  RGB production, reference;
};

// Image means over rows [first_row, resolution.y) of the production render and the delta-
// tracking reference.
Comparison compare_builtin(const char* name, Vec2i resolution, int production_spp, int reference_spp,
                           int max_bounces, int first_row = 0) {
  const SceneDesc desc = parse_builtin(*find_builtin(name));
  const auto scene = Scene::build(desc);
  RenderSettings settings = default_settings(desc);
  settings.resolution = resolution;
  settings.spp = production_spp;
  settings.max_volume_bounces = max_bounces;
  const Image image = render(*scene, settings).image;
  ReferenceOptions options;
  options.estimator = ReferenceEstimator::kDeltaTracking;
  options.samples_per_pixel = reference_spp;
  options.max_bounces = max_bounces;
  options.max_surface_bounces = desc.render.max_depth;
  options.seed = 77;
  const std::vector<RGB> reference = reference_image(*scene, resolution, options);
  Comparison c;
  for (int y = first_row; y < resolution.y; ++y)
    for (int x = 0; x < resolution.x; ++x) {
      c.production += image.rgb(x, y, 0);
      c.reference += reference[size_t(y) * size_t(resolution.x) + size_t(x)];
    }
  return c;
}

void expect_close(RGB a, RGB b, float relative) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], relative * b[c]) << "channel " << c;
}

// Two overlapping chromatic boxes, a point light outside them and a dim sky: multiple
// scattering. Tolerance 2% of the image mean (measured spread of either estimator ~0.5%).
TEST(BuiltinScenes, OverlapAgreesWithDeltaTracking) {
  const Comparison c = compare_builtin("overlap", {24, 18}, 256, 2048, 64);
  expect_close(c.production, c.reference, 0.02f);
}

// Single scattering of a spot light past an occluder, plus direct light on the floor. The
// top third of the image, around the spot's apex, is left out: camera rays passing close to
// a point-like light inside a medium give both estimators heavy-tailed noise there (spread
// over seeds about 5 %, against about 1 % below it). Tolerance 3 %.
TEST(BuiltinScenes, SpotShaftsAgreesWithDeltaTracking) {
  const SceneDesc desc = parse_builtin(*find_builtin("spot-shafts"));
  ASSERT_EQ(desc.render.max_depth, 1);
  ASSERT_EQ(desc.render.max_volume_bounces, 1);
  const Comparison c = compare_builtin("spot-shafts", {24, 18}, 512, 2048, 1, 6);
  expect_close(c.production, c.reference, 0.03f);
}

}  // namespace
}  // namespace caligo
