#include "hybrid/textured_spot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "hybrid/mesh_edges.h"
#include "hybrid/shadow_volume.h"
#include "hybrid/shadow_volume_testing.h"
#include "lights/light_profile.h"
#include "media/phase.h"
#include "realtime/light_volume.h"
#include "realtime/scene_buffers.h"

namespace caligo {
namespace {

constexpr AirlightMedium kFog{0.1f, 0.15f};
constexpr int kSize = 64;

// A downward spot over a ground plane (y = 0), seen from the side; right = cross(dir, up) = +x,
// so the gobo's u grows with world x and with image x.
SpotLight make_spot(float outer_deg = 25.0f, float inner_deg = 20.0f) {
  SpotLight s;
  s.position = {0, 6, 0};
  s.direction = {0, -1, 0};
  s.up = {0, 0, -1};
  s.cos_outer = std::cos(radians(outer_deg));
  s.cos_inner = std::cos(radians(inner_deg));
  s.intensity = RGB(30.0f, 24.0f, 18.0f);
  return s;
}

struct Scene {
  RasterScene raster;
  View view;
  Plane depth;
};

Scene make_scene(const std::vector<TriangleMesh>& occluders, Vec3 eye = {0, 3, 12}, Vec3 target = {0, 2, 0}) {
  Scene s;
  const Vec3 up{0, 1, 0};
  const float g = 40.0f;
  s.raster.add_triangle({-g, 0, -g}, {-g, 0, g}, {g, 0, g}, up, up, up, 0);
  s.raster.add_triangle({-g, 0, -g}, {g, 0, g}, {g, 0, -g}, up, up, up, 0);
  for (const auto& o : occluders)
    for (size_t t = 0; t < o.triangle_count(); ++t)
      s.raster.add_triangle(o.positions[o.indices[3 * t]], o.positions[o.indices[3 * t + 1]],
                            o.positions[o.indices[3 * t + 2]], up, up, up, 0);
  s.view = View::perspective_view(eye, normalize(target - eye), up, radians(50.0f), {kSize, kSize});
  s.depth = rasterize_depth(s.raster, s.view);
  return s;
}

float ray_end(const Scene& s, const Ray& ray, int x, int y, float max_distance = 1000.0f) {
  const float d = s.depth.at(x, y);
  return d < kSkyDepth ? std::min(d / s.view.depth_per_t(ray.direction), max_distance) : max_distance;
}

// The ray's stretch inside the spot's cone, clipped to the surface (light_volume_interval, whose
// agreement with delta_arrival along whole rays OnlyRaysInsideTheConeAreMarched checks).
std::optional<RayRange> cone_span(const Scene& s, const SpotLight& spot, int x, int y) {
  const Ray ray = s.view.ray({float(x) + 0.5f, float(y) + 0.5f});
  return light_volume_interval(ShadedLight{spot}, ray.origin, ray.direction, 0.0f, ray_end(s, ray, x, y));
}

constexpr ScatteringMedium kGreyFog{RGB(kFog.sigma_s), RGB(kFog.sigma_t), IsotropicPhase{}};

// The single-scattering integral with the path tracer's light model (delta_arrival includes
// cone, gobo and 1/d²) and phase_eval, midpoint rule in double with `n` samples over the cone
// stretch (over a whole ray, 4000 samples were 25% off next to the apex, where the cone is
// crossed in 0.2 m).
RGB reference_integral(const Scene& s, const SpotLight& spot, int x, int y, int n,
                       const ScatteringMedium& medium = kGreyFog) {
  const auto span = cone_span(s, spot, x, y);
  if (!span) return RGB(0.0f);
  const Ray ray = s.view.ray({float(x) + 0.5f, float(y) + 0.5f});
  const double dt = double(span->t1 - span->t0) / n;
  double sum[3] = {0, 0, 0};
  for (int i = 0; i < n; ++i) {
    const double t = span->t0 + (i + 0.5) * dt;
    const Vec3 p = ray.origin + ray.direction * float(t);
    const auto a = delta_arrival(spot, p);
    if (!a) continue;
    const double phase = phase_eval(medium.phase, -a->wi, -ray.direction);
    for (int c = 0; c < 3; ++c)
      sum[c] += a->radiance[c] * medium.sigma_s[c] * phase * std::exp(-double(medium.sigma_t[c]) * (t + a->distance)) * dt;
  }
  return RGB(float(sum[0]), float(sum[1]), float(sum[2]));
}

// The brute-force march of the same model: `n` equal steps over the cone stretch, visibility
// and emitted colour at each midpoint, the step's airlight in closed form.
RGB brute_march(const Scene& s, const SpotLight& spot, const ShadowMap* shadow, const AirlightTable& table,
                int x, int y, int n) {
  const auto span = cone_span(s, spot, x, y);
  if (!span) return RGB(0.0f);
  const Ray ray = s.view.ray({float(x) + 0.5f, float(y) + 0.5f});
  const float dt = (span->t1 - span->t0) / float(n);
  const AirlightRay air = make_airlight_ray(table, kFog, 1.0f, spot.position, ray.origin, ray.direction);
  RGB sum(0.0f);
  for (int i = 0; i < n; ++i) {
    const float t0 = span->t0 + float(i) * dt;
    const Vec3 p = ray.origin + ray.direction * (t0 + 0.5f * dt);
    const auto a = delta_arrival(spot, p);
    if (!a || (shadow && shadow->visibility(p) < 0.5f)) continue;
    sum += a->radiance * (a->distance * a->distance) * airlight_interval(table, air, t0, t0 + dt);
  }
  return sum;
}

std::shared_ptr<const GoboImage> solid_gobo(int w, int h, RGB c) {
  return std::make_shared<const GoboImage>(w, h, std::vector<RGB>(size_t(w) * size_t(h), c));
}

// Per-channel absolute error of an image against a per-pixel reference: sums and maxima.
struct ErrorStats {
  double ref_sum = 0, err_sum = 0, ref_max = 0, err_max = 0;
};
template <typename Reference>
ErrorStats error_stats(const ColorPlanes& got, Reference&& reference) {
  ErrorStats e;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const RGB ref = reference(x, y), value = got.at(x, y);
      for (int c = 0; c < 3; ++c) {
        e.ref_sum += ref[c];
        e.err_sum += std::abs(value[c] - ref[c]);
        e.ref_max = std::max<double>(e.ref_max, ref[c]);
        e.err_max = std::max<double>(e.err_max, std::abs(value[c] - ref[c]));
      }
    }
  return e;
}

double luminance_sum(const ColorPlanes& c) {
  double s = 0;
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x) s += c.r.at(x, y) + c.g.at(x, y) + c.b.at(x, y);
  return s;
}

TEST(TexturedSpot, StepRuleGoesFromMinAlongTheAxisToMaxAcrossIt) {
  TexturedSpotSettings s;
  s.min_steps = 10;
  s.max_steps = 150;
  EXPECT_EQ(textured_spot_steps(1.0f, s), 10);
  EXPECT_EQ(textured_spot_steps(-1.0f, s), 10);
  EXPECT_EQ(textured_spot_steps(0.0f, s), 150);
  int last = 0;
  for (float c = 1.0f; c >= 0.0f; c -= 0.05f) {
    const int n = textured_spot_steps(c, s);
    EXPECT_GE(n, last);
    last = n;
  }
  EXPECT_EQ(textured_spot_steps(std::nanf(""), s), 150);
}

TEST(TexturedSpot, MipChainBoxFiltersAndKeepsTheMean) {
  std::vector<RGB> px;
  for (int i = 0; i < 15; ++i) px.push_back(RGB(float(i), float(i * i % 7), 1.0f));
  const GoboImage img(5, 3, px);
  const auto chain = gobo_mip_chain(img);
  ASSERT_EQ(chain.size(), 3u);
  EXPECT_EQ(chain[1].width(), 2);
  EXPECT_EQ(chain[1].height(), 1);
  EXPECT_EQ(chain[2].width(), 1);
  // Equal blocks (6x4 -> 3x2 -> 1x1) keep the mean exactly.
  std::vector<RGB> even;
  for (int i = 0; i < 24; ++i) even.push_back(RGB(float(i), float(i * i % 7), 1.0f));
  const GoboImage even_img(6, 4, even);
  const auto even_chain = gobo_mip_chain(even_img);
  ASSERT_EQ(even_chain.size(), 3u);
  for (const auto& level : even_chain) {
    EXPECT_NEAR(level.mean().r, even_img.mean().r, 1e-4f);
    EXPECT_NEAR(level.mean().g, even_img.mean().g, 1e-4f);
  }
  // Level 1 texel 0 averages source columns 0..1 of all 3 rows.
  EXPECT_NEAR(chain[1].pixel(0, 0).r, (0 + 1 + 5 + 6 + 10 + 11) / 6.0f, 1e-5f);
  EXPECT_EQ(gobo_mip_chain(img, 2).size(), 2u);
}

// (1) A white gobo at blur 0, no occluder, against an 8000-sample integration of the same
// integral with delta_arrival: the only errors are colour held constant over a step and the
// airlight table.
TEST(TexturedSpot, WhiteGoboMatchesTheSingleScatteringIntegral) {
  const Scene s = make_scene({});
  SpotLight spot = make_spot();
  spot.gobo.image = solid_gobo(4, 4, RGB(1.0f));
  TexturedSpotSettings settings;
  settings.blur_level = 0;
  const auto& table = AirlightTable::shared();
  const ScatterResult r = scatter_textured_spot(s.view, s.depth, nullptr, table, kFog, spot, settings);
  const auto [ref_sum, err_sum, ref_max, err_max] =
      error_stats(r.radiance, [&](int x, int y) { return reference_integral(s, spot, x, y, 8000); });
  const double total = luminance_sum(r.radiance);
  std::printf(
      "white gobo: total %.5g vs %.5g (%.3f%%), mean |err| %.3f%% of mean, max |err| %.3f%% of max, "
      "%d marched pixels, %lld lookups\n",
      total, ref_sum, 100 * (total / ref_sum - 1), 100 * err_sum / ref_sum, 100 * err_max / ref_max,
      r.marched_pixels, (long long)r.total_lookups);
  ASSERT_GT(ref_sum, 0.0);
  // Measured: total -0.001%, mean |err| 0.035%, max 0.05%.
  EXPECT_NEAR(total / ref_sum, 1.0, 0.003);
  EXPECT_LT(err_sum / ref_sum, 0.005);
  EXPECT_LT(err_max / ref_max, 0.01);
  // A white gobo blurred is still white: blur changes nothing.
  settings.blur_level = 2;
  const ScatterResult blurred = scatter_textured_spot(s.view, s.depth, nullptr, table, kFog, spot, settings);
  EXPECT_NEAR(luminance_sum(blurred.radiance) / total, 1.0, 1e-5);
}

// Per-interval blur against the brute-force textured march: a 64x64 checkerboard gobo marched
// in 6 steps per ray aliases (each step reads one point of many squares); with the footprint's
// mip level each coarse step reads the squares' average, much closer to a 600-step march of the
// exact texture. At 600 steps every footprint is under two texels: the same image.
TEST(TexturedSpot, PerIntervalBlurFollowsTheBruteForceMarch) {
  const Scene s = make_scene({});
  SpotLight spot = make_spot();
  spot.intensity = RGB(30.0f);
  std::vector<RGB> px(64 * 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) px[size_t(y * 64 + x)] = RGB(((x / 2 + y / 2) % 2) ? 1.0f : 0.1f);
  spot.gobo.image = std::make_shared<const GoboImage>(64, 64, px);
  const auto& table = AirlightTable::shared();
  const auto run = [&](int steps, bool per_interval) {
    TexturedSpotSettings settings;
    settings.min_steps = settings.max_steps = steps;
    settings.blur_level = 0;
    settings.jitter = 0.0f;
    settings.blur_per_interval = per_interval;
    return scatter_textured_spot(s.view, s.depth, nullptr, table, kFog, spot, settings).radiance;
  };
  const ColorPlanes brute = run(600, false), fine = run(600, true), point = run(6, false), blurred = run(6, true);
  double e_point = 0.0, e_blurred = 0.0, e_fine = 0.0, total = 0.0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const double b = brute.at(x, y).g;
      total += b * b;
      e_point += sqr(point.at(x, y).g - b);
      e_blurred += sqr(blurred.at(x, y).g - b);
      e_fine += sqr(fine.at(x, y).g - b);
    }
  ASSERT_GT(total, 0.0);
  std::printf("checkerboard gobo, relative RMSE against 600 steps: 6 steps %.4f, with per-interval blur %.4f; "
              "600 steps with it %.2g\n",
              std::sqrt(e_point / total), std::sqrt(e_blurred / total), std::sqrt(e_fine / total));
  EXPECT_LT(e_blurred, 0.5 * e_point);
  EXPECT_LT(std::sqrt(e_fine / total), 1e-3);
}

// (2) Rays that miss the cone cost nothing and get nothing; rays that see light get marched.
TEST(TexturedSpot, OnlyRaysInsideTheConeAreMarched) {
  const Scene s = make_scene({});
  const SpotLight spot = make_spot(10.0f, 7.0f);
  TexturedSpotSettings settings;
  const ScatterResult r =
      scatter_textured_spot(s.view, s.depth, nullptr, AirlightTable::shared(), kFog, spot, settings);
  int lit_rays = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const Ray ray = s.view.ray({float(x) + 0.5f, float(y) + 0.5f});
      const float t_end = ray_end(s, ray, x, y);
      bool sees_light = false;
      for (int i = 0; i < 2000 && !sees_light; ++i)
        sees_light =
            delta_arrival(spot, ray.origin + ray.direction * ((float(i) + 0.5f) * t_end / 2000)).has_value();
      lit_rays += sees_light;
      const int n = r.lookups_at(x, y);
      if (sees_light) {
        EXPECT_GT(n, 0) << x << "," << y;
      }
      if (n == 0) {
        EXPECT_FALSE(sees_light) << x << "," << y;
        EXPECT_EQ(r.radiance.at(x, y), RGB(0.0f)) << x << "," << y;
      } else {
        EXPECT_GE(n, settings.min_steps);
        EXPECT_LE(n, settings.max_steps);
      }
    }
  std::printf("narrow cone: %d of %d pixels marched (%d see light), %lld lookups\n", r.marched_pixels,
              kSize * kSize, lit_rays, (long long)r.total_lookups);
  EXPECT_GT(r.marched_pixels, kSize * kSize / 20);
  EXPECT_LT(r.marched_pixels, kSize * kSize / 2);
}

// (3) Left half red, right half blue: the shafts on the left of the image are red, on the
// right blue. The coarsest mip level (1x1, the mean) mixes them.
TEST(TexturedSpot, TwoColourGoboGivesColouredShaftsOnTheirSides) {
  const Scene s = make_scene({});
  SpotLight spot = make_spot();
  spot.intensity = RGB(30.0f);
  std::vector<RGB> px(64);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) px[size_t(y * 8 + x)] = x < 4 ? RGB(1, 0, 0) : RGB(0, 0, 1);
  spot.gobo.image = std::make_shared<const GoboImage>(8, 8, px);
  auto halves = [&](int blur, double out[2][2]) {
    TexturedSpotSettings settings;
    settings.blur_level = blur;
    const ScatterResult r =
        scatter_textured_spot(s.view, s.depth, nullptr, AirlightTable::shared(), kFog, spot, settings);
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const RGB c = r.radiance.at(x, y);
        out[x < kSize / 2][0] += c.r;
        out[x < kSize / 2][1] += c.b;
      }
  };
  double exact[2][2] = {}, mean[2][2] = {};
  halves(0, exact);
  halves(3, mean);
  std::printf("two-colour gobo: left red/blue %.3g/%.3g, right %.3g/%.3g; blurred to 1x1: left %.3g/%.3g\n",
              exact[1][0], exact[1][1], exact[0][0], exact[0][1], mean[1][0], mean[1][1]);
  EXPECT_GT(exact[1][0], 5 * exact[1][1]);  // left: red
  EXPECT_GT(exact[0][1], 5 * exact[0][0]);  // right: blue
  EXPECT_NEAR(mean[1][0] / mean[1][1], 1.0, 1e-3);
  // The box filter keeps the mean: total flux is unchanged by the blur.
  EXPECT_NEAR((mean[0][0] + mean[0][1] + mean[1][0] + mean[1][1]) /
                  (exact[0][0] + exact[0][1] + exact[1][0] + exact[1][1]),
              1.0, 0.02);
}

// A 30-degree spot through a 16x16 colour-gradient gobo (both occluder tests).
SpotLight gradient_spot() {
  SpotLight spot = make_spot(30.0f, 22.0f);
  std::vector<RGB> px(16 * 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) px[size_t(y * 16 + x)] = RGB(0.2f + 0.05f * x, 1.0f - 0.05f * y, 0.5f);
  spot.gobo.image = std::make_shared<const GoboImage>(16, 16, px);
  return spot;
}

// (4) An occluder in the cone: agreement with a 400-step brute-force march of the same model.
TEST(TexturedSpot, ShadowedSpotMatchesBruteForceMarch) {
  const Scene s = make_scene({testing::box_mesh({-0.6f, 3.0f, -0.6f}, {0.4f, 3.4f, 0.4f})});
  const SpotLight spot = gradient_spot();
  const auto map = render_shadow_map(s.raster, ShadedLight{spot}, 512, s.raster.bounds());
  ASSERT_TRUE(map);
  const auto& table = AirlightTable::shared();
  TexturedSpotSettings settings;
  settings.blur_level = 0;
  const ScatterResult r = scatter_textured_spot(s.view, s.depth, &*map, table, kFog, spot, settings);
  const ScatterResult open = scatter_textured_spot(s.view, s.depth, nullptr, table, kFog, spot, settings);
  const auto [ref_sum, err_sum, ref_max, err_max] =
      error_stats(r.radiance, [&](int x, int y) { return brute_march(s, spot, &*map, table, x, y, 400); });
  const double total = luminance_sum(r.radiance), unshadowed = luminance_sum(open.radiance);
  std::printf(
      "shadowed: total %.5g vs brute %.5g (%.3f%%), mean |err| %.3f%% of mean, max |err| %.2f%% of max; "
      "shadow removes %.1f%%; %lld lookups vs %d for 400 per pixel\n",
      total, ref_sum, 100 * (total / ref_sum - 1), 100 * err_sum / ref_sum, 100 * err_max / ref_max,
      100 * (1 - total / unshadowed), (long long)r.total_lookups, 400 * kSize * kSize);
  EXPECT_LT(total, 0.95 * unshadowed);  // the occluder matters
  // Measured: total -0.002%, mean |err| 0.09%, max 0.06% (shadow edges move by under a step).
  EXPECT_NEAR(total / ref_sum, 1.0, 0.005);
  EXPECT_LT(err_sum / ref_sum, 0.01);
  EXPECT_LT(err_max / ref_max, 0.05);
  EXPECT_LT(r.total_lookups, 400 * kSize * kSize / 4);
}

// (4b) The same scene with the spot's shadow volumes: the stretches before and after them skip
// the shadow map (and, at lit_rate < 1, take fewer steps); the answer stays that of the march.
TEST(TexturedSpot, ShadowVolumeSegmentsMatchBruteForceMarch) {
  const TriangleMesh box = testing::box_mesh({-0.6f, 3.0f, -0.6f}, {0.4f, 3.4f, 0.4f});
  const Scene s = make_scene({box});
  const SpotLight spot = gradient_spot();
  const auto map = render_shadow_map(s.raster, ShadedLight{spot}, 512, s.raster.bounds());
  ASSERT_TRUE(map);
  const ShadowVolume volume = build_shadow_volume(MeshEdges(box), spot.position, 40.0f);
  const ShadowVolumeBuffers buffers = rasterize_shadow_volumes({&volume, 1}, s.view, s.depth);
  const auto& table = AirlightTable::shared();
  TexturedSpotSettings settings;
  settings.blur_level = 0;
  const ScatterResult plain = scatter_textured_spot(s.view, s.depth, &*map, table, kFog, spot, settings);
  for (float lit_rate : {1.0f, 0.5f}) {
    settings.lit_rate = lit_rate;
    const ScatterResult r = scatter_textured_spot(s.view, s.depth, &*map, table, kFog, spot, settings, &buffers);
    const auto [ref_sum, err_sum, ref_max, err_max] =
        error_stats(r.radiance, [&](int x, int y) { return brute_march(s, spot, &*map, table, x, y, 400); });
    const double total = luminance_sum(r.radiance);
    std::printf("volumes, lit_rate %.1f: total %.3f%% off brute, mean |err| %.3f%%, max %.2f%%; %lld steps vs %lld\n",
                lit_rate, 100 * (total / ref_sum - 1), 100 * err_sum / ref_sum, 100 * err_max / ref_max,
                (long long)r.total_lookups, (long long)plain.total_lookups);
    // Bounds of the plain pass's test (4); lit_rate 0.5 halves the steps where only the gobo
    // varies, so it gets twice the room (measured: mean |err| 0.07 % and 0.11 % at 1 and 0.5).
    const double room = lit_rate < 1.0f ? 2.0 : 1.0;
    EXPECT_NEAR(total / ref_sum, 1.0, 0.005 * room);
    EXPECT_LT(err_sum / ref_sum, 0.01 * room);
    EXPECT_LT(err_max / ref_max, 0.05 * room);
    if (lit_rate < 1.0f) {
      EXPECT_LT(r.total_lookups, plain.total_lookups * 3 / 4);
    }
  }
  // A pixel no volume covers (eye outside all) takes its whole stretch at the lit rate.
  settings.lit_rate = 0.5f;
  const ScatterResult r = scatter_textured_spot(s.view, s.depth, &*map, table, kFog, spot, settings, &buffers);
  int checked = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      if (!buffers.covered(x, y) && plain.lookups_at(x, y) > 0) {
        EXPECT_EQ(r.lookups_at(x, y), (plain.lookups_at(x, y) + 1) / 2) << x << "," << y;
        ++checked;
      }
  EXPECT_GT(checked, 0);
  const ShadowVolumeBuffers empty;
  EXPECT_THROW(scatter_textured_spot(s.view, s.depth, &*map, table, kFog, spot, settings, &empty),
               std::invalid_argument);
}

// (5) Extreme inputs: never NaN, never negative.
TEST(TexturedSpot, ExtremeInputsStayFiniteAndNonNegative) {
  auto check = [](const ScatterResult& r, const char* what) {
    double sum = 0;
    for (int y = 0; y < r.radiance.height(); ++y)
      for (int x = 0; x < r.radiance.width(); ++x) {
        const RGB c = r.radiance.at(x, y);
        for (int k = 0; k < 3; ++k) {
          EXPECT_TRUE(std::isfinite(c[k])) << what << " " << x << "," << y;
          EXPECT_GE(c[k], 0.0f) << what << " " << x << "," << y;
          sum += c[k];
        }
      }
    return sum;
  };
  const auto& table = AirlightTable::shared();
  SpotLight spot = make_spot();
  spot.gobo.image = solid_gobo(3, 5, RGB(0.3f, 1.0f, 2.0f));
  // Eye at the light, looking down the axis; eye on the axis below, looking up through the light.
  const Scene at_light = make_scene({}, spot.position + Vec3(0.0f, -1e-4f, 0.0f), {0, 0, 0.05f});
  EXPECT_GT(
      check(scatter_textured_spot(at_light.view, at_light.depth, nullptr, table, kFog, spot), "at light"), 0);
  const Scene below = make_scene({}, {0, 2, 0}, {0, 10, 0.05f});
  EXPECT_GT(check(scatter_textured_spot(below.view, below.depth, nullptr, table, kFog, spot), "looking up"),
            0);
  const Scene side = make_scene({});
  check(scatter_textured_spot(side.view, side.depth, nullptr, table, {0.1f, 0.0f}, spot), "sigma_t 0");
  check(scatter_textured_spot(side.view, side.depth, nullptr, table, {5.0f, 50.0f}, spot), "sigma_t 50");
  SpotLight wide = spot;
  wide.cos_outer = -0.3f;
  wide.cos_inner = 0.2f;
  check(scatter_textured_spot(side.view, side.depth, nullptr, table, kFog, wide), "wider than 90");
  Plane sky(kSize, kSize, kSkyDepth), nan_depth(kSize, kSize, std::nanf(""));
  check(scatter_textured_spot(side.view, sky, nullptr, table, kFog, spot), "sky");
  check(scatter_textured_spot(side.view, nan_depth, nullptr, table, kFog, spot), "nan depth");
  TexturedSpotSettings odd;
  odd.min_steps = -4;
  odd.max_steps = 0;
  odd.jitter = 7.0f;
  odd.blur_level = 99;
  odd.max_distance = -1.0f;
  check(scatter_textured_spot(side.view, side.depth, nullptr, table, kFog, spot, odd), "odd settings");
  EXPECT_THROW(scatter_textured_spot(side.view, Plane(3, 3), nullptr, table, kFog, spot),
               std::invalid_argument);
}

// Hoffman and Preetham's per-step model (the paper's for coloured lights): in the grey,
// isotropic fog of the white-gobo test it matches the single-scattering integral nearly as the
// airlight does (its further error: 1/d² held over a step); in a coloured, forward-scattering
// medium, which the airlight cannot take in one pass, it matches the integral with that phase,
// and the phase matters (the isotropic answer is far off).
TEST(TexturedSpot, HoffmanPreethamMatchesTheIntegralWithAnyPhaseAndColour) {
  const Scene s = make_scene({});
  SpotLight spot = make_spot();
  spot.gobo.image = solid_gobo(4, 4, RGB(1.0f));
  TexturedSpotSettings settings;
  settings.blur_level = 0;
  settings.model = SpotScatterModel::kHoffmanPreetham;
  const auto report = [&](const char* what, const ScatteringMedium& m, const ColorPlanes& got) {
    const ErrorStats e = error_stats(got, [&](int x, int y) { return reference_integral(s, spot, x, y, 8000, m); });
    std::printf("%s: total %+.3f%%, mean |err| %.3f%% of mean, max |err| %.3f%% of max\n", what,
                100 * (luminance_sum(got) / e.ref_sum - 1), 100 * e.err_sum / e.ref_sum, 100 * e.err_max / e.ref_max);
    EXPECT_GT(e.ref_sum, 0.0);
    return e;
  };
  const ErrorStats grey =
      report("H&P, grey fog", kGreyFog, scatter_textured_spot(s.view, s.depth, nullptr, kGreyFog, spot, settings).radiance);
  // Measured (2026-12): total +0.000%, mean |err| 0.031%, max |err| 0.009% (the airlight: 0.035%,
  // 0.046%, its table's interpolation); held to ~3x.
  EXPECT_LT(grey.err_sum / grey.ref_sum, 0.001);
  EXPECT_LT(grey.err_max / grey.ref_max, 0.0005);

  const ScatteringMedium coloured{RGB(0.05f, 0.1f, 0.2f), RGB(0.08f, 0.15f, 0.3f), HenyeyGreensteinPhase{0.6f}};
  const ScatterResult hp = scatter_textured_spot(s.view, s.depth, nullptr, coloured, spot, settings);
  const ErrorStats e = report("H&P, coloured HG 0.6 fog", coloured, hp.radiance);
  // Measured (2026-12): mean |err| 0.022%, max |err| 0.006%; held to ~3x.
  EXPECT_LT(e.err_sum / e.ref_sum, 0.001);
  EXPECT_LT(e.err_max / e.ref_max, 0.0005);
  // The same medium read as isotropic is far from it: the test sees the phase.
  ScatteringMedium isotropic = coloured;
  isotropic.phase = IsotropicPhase{};
  const ColorPlanes flat = scatter_textured_spot(s.view, s.depth, nullptr, isotropic, spot, settings).radiance;
  const ErrorStats off = error_stats(flat, [&](int x, int y) { return reference_integral(s, spot, x, y, 2000, coloured); });
  EXPECT_GT(off.err_sum / off.ref_sum, 0.2);

  // The apex in view, where 1/d² varies most across a step. Measured (2026-12): mean |err|
  // 0.023%, max 0.005%: near the apex the cone is narrow, so its stretch, and every step of it,
  // is short against d too.
  const Scene near = make_scene({}, {1.5f, 6.5f, 3.0f}, {0.0f, 5.0f, 0.0f});
  const ColorPlanes apex = scatter_textured_spot(near.view, near.depth, nullptr, coloured, spot, settings).radiance;
  const ErrorStats ea = error_stats(apex, [&](int x, int y) { return reference_integral(near, spot, x, y, 8000, coloured); });
  std::printf("H&P, apex in view: mean |err| %.3f%% of mean, max |err| %.3f%% of max\n", 100 * ea.err_sum / ea.ref_sum,
              100 * ea.err_max / ea.ref_max);
  EXPECT_LT(ea.err_sum / ea.ref_sum, 0.001);
  EXPECT_LT(ea.err_max / ea.ref_max, 0.0005);
}

// kAuto: the airlight for a grey isotropic medium, Hoffman–Preetham otherwise; a coloured medium
// under the airlight is three passes whose channels match Hoffman–Preetham's one.
TEST(TexturedSpot, AutoModelPicksByMediumAndTheTwoModelsAgree) {
  ScatteringMedium m = kGreyFog;
  EXPECT_EQ(resolve_spot_model(SpotScatterModel::kAuto, m), SpotScatterModel::kAirlight);
  m.phase = HenyeyGreensteinPhase{0.3f};
  EXPECT_EQ(resolve_spot_model(SpotScatterModel::kAuto, m), SpotScatterModel::kHoffmanPreetham);
  m = kGreyFog;
  m.sigma_s = RGB(0.1f, 0.1f, 0.12f);
  EXPECT_EQ(resolve_spot_model(SpotScatterModel::kAuto, m), SpotScatterModel::kHoffmanPreetham);
  EXPECT_EQ(resolve_spot_model(SpotScatterModel::kAirlight, m), SpotScatterModel::kAirlight);

  const Scene s = make_scene({testing::box_mesh({-0.6f, 3.0f, -0.6f}, {0.4f, 3.4f, 0.4f})});
  const SpotLight spot = gradient_spot();
  const auto map = render_shadow_map(s.raster, ShadedLight{spot}, 512, s.raster.bounds());
  ASSERT_TRUE(map);
  TexturedSpotSettings settings;
  settings.model = SpotScatterModel::kAirlight;
  const ScatterResult air = scatter_textured_spot(s.view, s.depth, &*map, m, spot, settings);
  settings.model = SpotScatterModel::kHoffmanPreetham;
  const ScatterResult hp = scatter_textured_spot(s.view, s.depth, &*map, m, spot, settings);
  EXPECT_EQ(air.total_lookups, 3 * hp.total_lookups);
  const ErrorStats e = error_stats(hp.radiance, [&](int x, int y) { return air.radiance.at(x, y); });
  std::printf("coloured fog, shadowed gradient spot: H&P against 3 airlight passes: mean |diff| %.3f%%, max %.3f%%\n",
              100 * e.err_sum / e.ref_sum, 100 * e.err_max / e.ref_max);
  ASSERT_GT(e.ref_sum, 0.0);
  // Measured (2026-12): mean 0.019%, max 0.065% (the two differ in 1/d² and e^{-σ_t d} over a
  // step, and the airlight's table interpolation); held to ~3x.
  EXPECT_LT(e.err_sum / e.ref_sum, 0.0006);
  EXPECT_LT(e.err_max / e.ref_max, 0.002);
  // The airlight is isotropic: asked for it with an anisotropic phase is a caller's bug.
  m.phase = HenyeyGreensteinPhase{0.3f};
  settings.model = SpotScatterModel::kAirlight;
  EXPECT_THROW(scatter_textured_spot(s.view, s.depth, &*map, m, spot, settings), std::invalid_argument);
}

}  // namespace
}  // namespace caligo
