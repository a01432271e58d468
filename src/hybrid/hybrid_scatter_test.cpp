#include "hybrid/hybrid_scatter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

#include "hybrid/shadow_volume_testing.h"
#include "realtime/scene_buffers.h"

namespace caligo {
namespace {

using testing::box_mesh;
using testing::DVec;
using testing::sphere_mesh;

constexpr AirlightMedium kFog{0.1f, 0.15f};

// A ground plane (y = 0) and closed occluders, lit by one point light, seen at 64 x 48.
struct Scene {
  std::vector<TriangleMesh> occluders;
  HybridLight light;
  View view;
  Plane depth;  // linear, rasterised
  ShadowMap shadow;
  ShadowVolumeBuffers volumes;
  Bounds3 bounds;
};

Scene make_scene(std::vector<TriangleMesh> occluders, Vec3 light, Vec3 eye, Vec3 target, int map_size = 512,
                 float ground = 40.0f) {
  Scene s;
  s.occluders = std::move(occluders);
  s.light = {light, 20.0f, RGB(1.0f, 0.5f, 0.25f)};
  RasterScene raster;
  const Vec3 up{0, 1, 0};
  raster.add_triangle({-ground, 0, -ground}, {-ground, 0, ground}, {ground, 0, ground}, up, up, up, 0);
  raster.add_triangle({-ground, 0, -ground}, {ground, 0, ground}, {ground, 0, -ground}, up, up, up, 0);
  for (const auto& o : s.occluders)
    for (size_t t = 0; t < o.triangle_count(); ++t)
      raster.add_triangle(o.positions[o.indices[3 * t]], o.positions[o.indices[3 * t + 1]],
                          o.positions[o.indices[3 * t + 2]], up, up, up, 0);
  s.bounds = raster.bounds();
  s.view = View::perspective_view(eye, normalize(target - eye), up, radians(50.0f), {64, 48});
  s.depth = rasterize_depth(raster, s.view);
  s.shadow = *render_shadow_map(raster, PointLight{light, RGB(1.0f)}, map_size, s.bounds);
  std::vector<ShadowVolume> volumes;
  for (const auto& o : s.occluders)
    volumes.push_back(build_shadow_volume(MeshEdges(o), light, extrusion_for(s.bounds, light)));
  s.volumes = rasterize_shadow_volumes(volumes, s.view, s.depth);
  return s;
}

// The paper's test scene: a sphere hanging over the ground, the light above and to the side;
// the camera looks down so every pixel sees ground (a finite ray for the brute force).
constexpr Vec3 kSphereCentre{0, 2.5f, 0};
constexpr float kSphereRadius = 1.5f;
Scene sphere_scene(int map_size = 512) {
  return make_scene({sphere_mesh(kSphereCentre, kSphereRadius, 3)}, {0.7f, 6.0f, 0.4f}, {0, 6, 7}, {0, 0, -1},
                    map_size);
}

HybridSettings fine(int samples) {
  HybridSettings h;
  h.samples = samples;
  h.brute_samples = samples;
  h.jitter = 0.0f;
  return h;
}

void expect_finite_non_negative(const ColorPlanes& c) {
  for (const Plane* p : {&c.r, &c.g, &c.b})
    for (float v : p->data) {
      ASSERT_TRUE(std::isfinite(v));
      ASSERT_GE(v, 0.0f);
    }
}

// The airlight of one step of `n` over [a, b] at its largest along the pixel's ray: the error
// one misplaced visibility change can cause.
float largest_step(const Scene& s, int x, int y, float a, float b, int n) {
  const Ray r = s.view.ray({float(x) + 0.5f, float(y) + 0.5f});
  const AirlightTable& table = AirlightTable::shared();
  const AirlightRay air =
      make_airlight_ray(table, kFog, s.light.intensity, s.light.position, r.origin, r.direction);
  float most = 0.0f;
  for (int i = 0; i < n; ++i)
    most = std::max(most, airlight_interval(table, air, a + (b - a) * float(i) / float(n),
                                            a + (b - a) * float(i + 1) / float(n)));
  return most;
}

float t_opaque(const Scene& s, int x, int y) {
  const Ray r = s.view.ray({float(x) + 0.5f, float(y) + 0.5f});
  return s.depth.at(x, y) / s.view.depth_per_t(r.direction);
}

struct Agreement {
  int pixels = 0, outliers = 0;
  double sum_a = 0, sum_b = 0;
};

// Per pixel: within two misplaced steps of each method (a convex occluder's shadow is entered
// and left once), with 1e-5 relative slack for float rounding. Outliers are counted, not
// failed: rays that graze the shadow's boundary see the shadow map's staircase (one texel
// of the 512² cube face) instead of the volume's exact outline over a long stretch.
Agreement compare_with_brute(const Scene& s, const ScatterResult& hybrid, const ScatterResult& brute,
                             const HybridSettings& h) {
  Agreement g;
  for (int y = 0; y < s.view.resolution.y; ++y)
    for (int x = 0; x < s.view.resolution.x; ++x) {
      const float a = hybrid.radiance.r.at(x, y), b = brute.radiance.r.at(x, y);
      g.sum_a += a;
      g.sum_b += b;
      ++g.pixels;
      const float t = std::min(t_opaque(s, x, y), h.max_distance);
      float tol = 2.0f * largest_step(s, x, y, 0.0f, t, h.brute_samples);
      if (s.volumes.covered(x, y))
        tol += 2.0f * largest_step(s, x, y, std::min(s.volumes.front.at(x, y), t),
                                   std::min(s.volumes.back.at(x, y), t), h.samples);
      tol = tol * s.light.color.r + 1e-5f * b;
      if (std::abs(a - b) > tol) ++g.outliers;
    }
  return g;
}

// --- 1. Nothing casts a shadow: everything is the closed form ----------------------------------

// The per-frame table (HybridSettings::frame_table, used where sigma_t D <= 5 when asked) against
// the closed form, unshadowed and through the brute-force march: within FrameAirlight's stated
// error, 0.6 % of the pixel's whole-ray airlight at sigma_t D = 5 (here sigma_t D is ~1).
TEST(HybridScatter, TheFrameTableAgreesWithTheClosedForm) {
  const Scene s = make_scene({}, {0.7f, 6.0f, 0.4f}, {0, 6, 7}, {0, 0, -1});
  HybridSettings tail, framed;
  tail.frame_table = false;
  framed.frame_table = true;
  const AirlightTable& table = AirlightTable::shared();
  const ColorPlanes exact = scatter_unshadowed(s.view, s.depth, table, kFog, s.light, tail);
  const ColorPlanes fast = scatter_unshadowed(s.view, s.depth, table, kFog, s.light, framed);
  const ScatterResult brute_exact = scatter_brute(s.view, s.depth, s.shadow, table, kFog, s.light, tail);
  const ScatterResult brute_fast = scatter_brute(s.view, s.depth, s.shadow, table, kFog, s.light, framed);
  int differ = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      const float e = exact.at(x, y).g;
      ASSERT_GT(e, 0.0f);
      EXPECT_NEAR(fast.at(x, y).g, e, 6e-3f * e) << x << "," << y;
      EXPECT_NEAR(brute_fast.radiance.at(x, y).g, brute_exact.radiance.at(x, y).g, 6e-3f * e) << x << "," << y;
      if (fast.at(x, y).g != e) ++differ;
    }
  EXPECT_GT(differ, 0);  // the table was used
}

TEST(HybridScatter, WithoutOccludersIsTheClosedFormWithNoLookups) {
  const Scene s = make_scene({}, {0.7f, 6.0f, 0.4f}, {0, 6, 7}, {0, 0, -1});
  HybridSettings h;
  h.frame_table = false;  // the closed form exactly (the default; the table's test is above)
  const AirlightTable& table = AirlightTable::shared();
  const ScatterResult hybrid = scatter_hybrid(s.view, s.depth, s.volumes, s.shadow, table, kFog, s.light, h);
  const ScatterResult brute = scatter_brute(s.view, s.depth, s.shadow, table, kFog, s.light, h);
  const ColorPlanes exact = scatter_unshadowed(s.view, s.depth, table, kFog, s.light, h);
  EXPECT_EQ(hybrid.total_lookups, 0);
  EXPECT_EQ(hybrid.marched_pixels, 0);
  EXPECT_EQ(brute.total_lookups, int64_t(h.brute_samples) * 64 * 48);
  expect_finite_non_negative(hybrid.radiance);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      // The closed form by hand: colour x intensity-scaled airlight over [0, t_opaque].
      const Ray r = s.view.ray({float(x) + 0.5f, float(y) + 0.5f});
      const float by_hand =
          airlight(table, make_airlight_ray(table, kFog, 20.0f, s.light.position, r.origin, r.direction),
                   t_opaque(s, x, y));
      ASSERT_GT(by_hand, 0.0f);
      EXPECT_EQ(hybrid.radiance.at(x, y).g, exact.at(x, y).g);
      EXPECT_NEAR(exact.at(x, y).r, by_hand, 1e-6f * by_hand);
      EXPECT_NEAR(exact.at(x, y).b, 0.25f * by_hand, 1e-6f * by_hand);
      // Every step lit: one run from 0 to the surface, the same closed form.
      EXPECT_NEAR(brute.radiance.at(x, y).g, exact.at(x, y).g, 1e-5f * exact.at(x, y).g) << x << "," << y;
    }
}

// --- 2. An occluder: the hybrid and the brute-force march agree --------------------------------

TEST(HybridScatter, SphereOccluderAgreesWithBruteForce) {
  const Scene s = sphere_scene();
  const HybridSettings h = fine(400);
  const AirlightTable& table = AirlightTable::shared();
  const ScatterResult hybrid = scatter_hybrid(s.view, s.depth, s.volumes, s.shadow, table, kFog, s.light, h);
  const ScatterResult brute = scatter_brute(s.view, s.depth, s.shadow, table, kFog, s.light, h);
  const ColorPlanes unshadowed = scatter_unshadowed(s.view, s.depth, table, kFog, s.light, h);
  expect_finite_non_negative(hybrid.radiance);
  expect_finite_non_negative(brute.radiance);
  const Agreement g = compare_with_brute(s, hybrid, brute, h);
  double sum_unshadowed = 0;
  for (float v : unshadowed.r.data) sum_unshadowed += v;
  std::printf("    %d covered pixels; mean hybrid %.6g, brute %.6g (%.3f%%), unshadowed %.6g; %d outliers\n",
              hybrid.marched_pixels, g.sum_a / g.pixels, g.sum_b / g.pixels,
              100.0 * (g.sum_a / g.sum_b - 1.0), sum_unshadowed / g.pixels, g.outliers);
  EXPECT_GT(hybrid.marched_pixels, 64 * 48 / 10) << "the shadow must be on screen";
  EXPECT_LT(sum_unshadowed - g.sum_b, 0.99 * sum_unshadowed) << "sanity";
  EXPECT_GT((sum_unshadowed - g.sum_b) / sum_unshadowed, 0.005) << "the shadow must remove light";
  EXPECT_NEAR(g.sum_a / g.sum_b, 1.0, 0.005);
  EXPECT_LE(g.outliers, g.pixels / 100);
}

// --- 3. Against exact visibility -----------------------------------------------------------------

bool occluded(const std::vector<TriangleMesh>& occluders, Vec3 p, Vec3 light, Vec3 centre, float radius) {
  // Bounding-sphere cull: the segment p -> light must pass within `radius` of the centre.
  const Vec3 d = light - p;
  const float s = std::clamp(dot(centre - p, d) / dot(d, d), 0.0f, 1.0f);
  if (length(p + d * s - centre) > radius) return false;
  const DVec o{p.x, p.y, p.z}, dd{d.x, d.y, d.z};
  for (const auto& m : occluders)
    for (size_t t = 0; t < m.triangle_count(); ++t)
      if (const auto hit =
              testing::intersect(o, dd, m.positions[m.indices[3 * t]], m.positions[m.indices[3 * t + 1]],
                                 m.positions[m.indices[3 * t + 2]]);
          hit && hit->t < 1.0)
        return true;
  return false;
}

// The integrand itself, in double: sigma_s I0 / (4 pi) e^{-sigma_t (t + d)} / d^2 (W/(m^2 sr) per m).
double in_scattering(const Scene& s, const Ray& r, double t) {
  const double px = r.origin.x + t * r.direction.x - s.light.position.x,
               py = r.origin.y + t * r.direction.y - s.light.position.y,
               pz = r.origin.z + t * r.direction.z - s.light.position.z;
  const double d2 = px * px + py * py + pz * pz;
  return double(kFog.sigma_s) * s.light.intensity / (4.0 * std::numbers::pi) *
         std::exp(-double(kFog.sigma_t) * (t + std::sqrt(d2))) / d2;
}

TEST(HybridScatter, SphereOccluderAgreesWithExactVisibility) {
  // Independent of both the shadow map and the airlight tables: the midpoint rule in double over
  // 20,000 steps with visibility by ray casting against the occluder's triangles.
  const Scene s = sphere_scene(1024);
  const HybridSettings h = fine(400);
  const AirlightTable& table = AirlightTable::shared();
  const ScatterResult hybrid = scatter_hybrid(s.view, s.depth, s.volumes, s.shadow, table, kFog, s.light, h);
  constexpr int kSteps = 20000;
  int checked = 0, shadowed = 0;
  double worst = 0;
  // Every fourth covered pixel of every fourth row.
  for (int y = 1; y < 48; y += 4)
    for (int x = 1; x < 64; x += 4) {
      if (!s.volumes.covered(x, y)) continue;
      const Ray r = s.view.ray({float(x) + 0.5f, float(y) + 0.5f});
      const double t_end = t_opaque(s, x, y), dt = t_end / kSteps;
      double sum = 0, unshadowed = 0;
      for (int i = 0; i < kSteps; ++i) {
        const double t = (i + 0.5) * dt;
        const double f = in_scattering(s, r, t) * dt;
        unshadowed += f;
        if (!occluded(s.occluders, r.at(float(t)), s.light.position, kSphereCentre, kSphereRadius * 1.001f))
          sum += f;
      }
      shadowed += sum < 0.99 * unshadowed;
      // Error relative to the pixel's unshadowed airlight. Budget: the airlight tables (~0.1 %),
      // 400 steps over [front, back] (one misplaced step at each shadow edge) and the 1024^2
      // cube map, whose depth test puts the shadow's edge within ~1.5 texels of the true one.
      const double err = std::abs(double(hybrid.radiance.r.at(x, y)) - sum) / unshadowed;
      worst = std::max(worst, err);
      EXPECT_LT(err, 0.01) << "pixel " << x << "," << y << ": hybrid " << hybrid.radiance.r.at(x, y)
                           << " exact " << sum << " unshadowed " << unshadowed;
      ++checked;
    }
  std::printf("    %d pixels against exact visibility (%d shadowed): worst error %.4f%% of the airlight\n",
              checked, shadowed, 100.0 * worst);
  EXPECT_GT(checked, 20);
  EXPECT_GT(shadowed, checked / 2);
}

// --- 4. The eye inside a shadow volume -----------------------------------------------------------

TEST(HybridScatter, CameraInsideTheShadowAgreesWithBruteForce) {
  const Scene s =
      make_scene({box_mesh({-1, 3, -1}, {1, 4, 1})}, {0, 10, 0}, {0.2f, 1.0f, 0.1f}, {0, 0, 5}, 1024);
  ASSERT_EQ(s.volumes.eye_count, 1);
  // The upper half of the image sees the sky: both passes take the ray as lit beyond 30 m, so
  // the brute force's 1200 steps (2.5 cm) resolve the shadow's exit ~1.5 m from the eye. What is
  // left is the shadow map's edge against the volume's exact one, where the brute force reads
  // the map beyond `back` and the hybrid does not: the mean differs by 0.54 % at 512², 0.04 %
  // at 1024² and 0.13 % at 2048² (it depends on where the texel edges fall).
  HybridSettings h = fine(400);
  h.brute_samples = 1200;
  h.max_distance = 30.0f;
  const AirlightTable& table = AirlightTable::shared();
  const ScatterResult hybrid = scatter_hybrid(s.view, s.depth, s.volumes, s.shadow, table, kFog, s.light, h);
  const ScatterResult brute = scatter_brute(s.view, s.depth, s.shadow, table, kFog, s.light, h);
  expect_finite_non_negative(hybrid.radiance);
  EXPECT_EQ(hybrid.marched_pixels, 64 * 48);  // every pixel starts in shadow
  const Agreement g = compare_with_brute(s, hybrid, brute, h);
  std::printf("    mean hybrid %.6g, brute %.6g (%.3f%%); %d outliers\n", g.sum_a / g.pixels,
              g.sum_b / g.pixels, 100.0 * (g.sum_a / g.sum_b - 1.0), g.outliers);
  EXPECT_NEAR(g.sum_a / g.sum_b, 1.0, 0.005);
  EXPECT_LE(g.outliers, g.pixels / 100);
  // Pixels whose whole ray stays in the shadow get nothing.
  int dark = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) dark += s.volumes.tail(x, y) > 0 && hybrid.radiance.r.at(x, y) == 0.0f;
  EXPECT_GT(dark, 0);
}

// --- 5. Work -------------------------------------------------------------------------------------

TEST(HybridScatter, LooksUpTheShadowMapOnlyOnCoveredPixels) {
  const Scene s = sphere_scene();
  HybridSettings h;
  h.samples = 37;
  const ScatterResult hybrid =
      scatter_hybrid(s.view, s.depth, s.volumes, s.shadow, AirlightTable::shared(), kFog, s.light, h);
  int covered = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      covered += s.volumes.covered(x, y);
      EXPECT_EQ(hybrid.lookups_at(x, y), s.volumes.covered(x, y) ? 37 : 0);
    }
  EXPECT_GT(covered, 0);
  EXPECT_LT(covered, 64 * 48);
  EXPECT_EQ(hybrid.marched_pixels, covered);
  EXPECT_EQ(hybrid.total_lookups, int64_t(covered) * 37);
}

TEST(HybridScatter, JitterDithersWithoutBias) {
  const Scene s = sphere_scene();
  HybridSettings still = fine(24), dithered = fine(24);
  dithered.jitter = 1.0f;
  const AirlightTable& table = AirlightTable::shared();
  const ScatterResult a = scatter_hybrid(s.view, s.depth, s.volumes, s.shadow, table, kFog, s.light, still);
  const ScatterResult b =
      scatter_hybrid(s.view, s.depth, s.volumes, s.shadow, table, kFog, s.light, dithered);
  const ScatterResult ref =
      scatter_hybrid(s.view, s.depth, s.volumes, s.shadow, table, kFog, s.light, fine(800));
  double sa = 0, sb = 0, sr = 0, differ = 0;
  for (size_t i = 0; i < a.radiance.r.data.size(); ++i) {
    sa += a.radiance.r.data[i];
    sb += b.radiance.r.data[i];
    sr += ref.radiance.r.data[i];
    differ += a.radiance.r.data[i] != b.radiance.r.data[i];
  }
  EXPECT_GT(differ, 0) << "jitter must move the samples";
  EXPECT_NEAR(sa / sr, 1.0, 0.01);
  EXPECT_NEAR(sb / sr, 1.0, 0.01);
}

TEST(HybridScatter, RejectsBuffersOfAnotherSize) {
  const Scene s = sphere_scene(64);
  const AirlightTable& table = AirlightTable::shared();
  const Plane wrong(10, 10, 1.0f);
  EXPECT_THROW(scatter_brute(s.view, wrong, s.shadow, table, kFog, s.light), std::invalid_argument);
  EXPECT_THROW(scatter_hybrid(s.view, wrong, s.volumes, s.shadow, table, kFog, s.light),
               std::invalid_argument);
  ShadowVolumeBuffers small = s.volumes;
  small.tail_count.resize(3);
  EXPECT_THROW(scatter_hybrid(s.view, s.depth, small, s.shadow, table, kFog, s.light), std::invalid_argument);
}

}  // namespace
}  // namespace caligo
