// light_profile_simd.h against lights/light_profile.h, lane by lane: gobo projections of
// spot and box lights (rotated, shifted, wrapping, non-square images) and IES profiles of
// every horizontal symmetry, over random directions inside and outside the measured ranges.
#include "realtime/light_profile_simd.h"

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <string>

#include "lights/light_profile.h"

namespace caligo {
namespace {

using B = xsimd::batch<float>;
constexpr int kLanes = int(B::size);

struct Lanes {
  alignas(32) float v[kLanes];
  B load() const { return B::load_aligned(v); }
};

std::array<float, kLanes> store(const B& b) {
  alignas(32) std::array<float, kLanes> out;
  b.store_aligned(out.data());
  return out;
}

// Relative 1e-4 with a floor of 1e-6 for values near zero (dark texels, cone edges).
void expect_close(float scalar, float simd, const std::string& what) {
  EXPECT_NEAR(simd, scalar, 1e-4f * std::abs(scalar) + 1e-6f) << what;
}

std::shared_ptr<const GoboImage> test_image(int w, int h, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<RGB> pixels(size_t(w) * h);
  for (RGB& p : pixels) p = RGB(u(rng), u(rng), u(rng));
  return std::make_shared<const GoboImage>(w, h, std::move(pixels));
}

// Random unit vectors within `max_angle` of `axis`.
Vec3 direction_near(Vec3 axis, float max_angle, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float cos_t = 1.0f - u(rng) * (1.0f - std::cos(max_angle));
  const float sin_t = std::sqrt(std::max(0.0f, 1.0f - cos_t * cos_t));
  return Frame::from_z(axis).to_world(spherical_direction(sin_t, cos_t, 2.0f * kPi * u(rng)));
}

TEST(LightProfileSimd, SpotGoboMatchesScalar) {
  SpotLight spot;
  spot.position = {1.0f, 4.0f, -2.0f};
  spot.direction = normalize(Vec3(0.2f, -1.0f, 0.4f));
  spot.up = normalize(cross(cross(spot.direction, Vec3(0, 0, 1)), spot.direction));
  spot.cos_outer = std::cos(radians(24.0f));
  spot.cos_inner = std::cos(radians(16.0f));
  spot.gobo.image = test_image(7, 5, 3);
  spot.gobo.rotation = 0.7f;
  spot.gobo.offset = {0.3f, -1.2f};
  const SpotGoboSampler sampler(spot);
  ASSERT_TRUE(sampler.has_image());
  std::mt19937 rng(11);
  // Out to twice the outer angle: the image wraps beyond the cone's square.
  for (int round = 0; round < 500; ++round) {
    Lanes x, y, z;
    std::array<Vec3, kLanes> w;
    for (int i = 0; i < kLanes; ++i) {
      w[i] = direction_near(spot.direction, radians(48.0f), rng);
      x.v[i] = w[i].x, y.v[i] = w[i].y, z.v[i] = w[i].z;
    }
    const RgbBatch simd = sampler.filter(x.load(), y.load(), z.load());
    const auto r = store(simd.r), g = store(simd.g), b = store(simd.b);
    for (int i = 0; i < kLanes; ++i) {
      const RGB scalar = gobo_filter(spot.gobo, spot_gobo_uv(spot, w[i]));
      expect_close(scalar.r, r[i], "r");
      expect_close(scalar.g, g[i], "g");
      expect_close(scalar.b, b[i], "b");
    }
  }
  // Behind the light's plane spot_gobo_uv gives (-1, -1); the one-call form agrees too.
  const Vec3 back = -spot.direction;
  const RgbBatch behind = spot_gobo_batch(spot, B(back.x), B(back.y), B(back.z));
  const RGB expected = gobo_filter(spot.gobo, {-1.0f, -1.0f});
  EXPECT_NEAR(store(behind.g)[3], expected.g, 1e-6f);
}

TEST(LightProfileSimd, BoxGoboAndMissingImagesMatchScalar) {
  BoxLight box;
  box.half_width = 1.3f;
  box.half_height = 0.6f;
  box.gobo.image = test_image(16, 9, 5);
  box.gobo.rotation = -2.1f;
  box.gobo.offset = {5.25f, 0.1f};
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int round = 0; round < 500; ++round) {
    Lanes x, y;
    for (int i = 0; i < kLanes; ++i) x.v[i] = u(rng) * box.half_width, y.v[i] = u(rng) * box.half_height;
    const RgbBatch simd = box_gobo_batch(box, x.load(), y.load());
    const auto r = store(simd.r), b = store(simd.b);
    for (int i = 0; i < kLanes; ++i) {
      const Vec2 uv{0.5f + 0.5f * x.v[i] / box.half_width, 0.5f + 0.5f * y.v[i] / box.half_height};
      const RGB scalar = gobo_filter(box.gobo, uv);
      expect_close(scalar.r, r[i], "r");
      expect_close(scalar.b, b[i], "b");
    }
  }
  // No image: white, as gobo_filter; non-finite coordinates: black, as GoboImage::lookup.
  EXPECT_EQ(store(GoboSampler(Gobo{}).filter(B(0.3f), B(0.2f)).g)[0], 1.0f);
  const float nan = std::nanf("");
  EXPECT_EQ(store(GoboSampler(box.gobo).filter(B(nan), B(0.2f)).r)[0], 0.0f);
  EXPECT_EQ(gobo_filter(box.gobo, {nan, 0.2f}).r, 0.0f);
}

// A type C file with the given tables (candela values as written).
std::string lm63(const std::string& vertical, const std::string& horizontal, int nv, int nh,
                 const std::string& candela) {
  return "IESNA:LM-63-2002\n[TEST] simd\nTILT=NONE\n1 1000 1 " + std::to_string(nv) + " " +
         std::to_string(nh) + " 1 2 0 0 0\n1.0 1.0 100\n" + vertical + "\n" + horizontal + "\n" + candela +
         "\n";
}

std::string random_candela(int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 100.0f);
  std::string s;
  for (int i = 0; i < count; ++i) s += std::to_string(u(rng)) + " ";
  return s;
}

TEST(LightProfileSimd, IesMatchesScalarForEverySymmetry) {
  // Uneven vertical steps, measured only to 150 degrees: directions beyond receive 0.
  const std::string vertical = "0 5 12 30 45 60 90 120 150";
  const struct {
    std::string horizontal;
    int nh;
  } tables[] = {{"0", 1}, {"0 30 90", 3}, {"0 45 90 135 180", 5}, {"0 60 120 180 240 300 360", 7}};
  std::mt19937 rng(7);
  for (const auto& table : tables) {
    IesAttachment ies;
    ies.profile = std::make_shared<const IesProfile>(IesProfile::parse(
        lm63(vertical, table.horizontal, 9, table.nh, random_candela(9 * table.nh, 17)), "t.ies"));
    ies.axis = normalize(Vec3(0.3f, -1.0f, 0.2f));
    const IesSampler sampler(ies);
    int dark = 0;
    for (int round = 0; round < 400; ++round) {
      Lanes x, y, z;
      std::array<Vec3, kLanes> w;
      for (int i = 0; i < kLanes; ++i) {
        w[i] = direction_near(ies.axis, kPi, rng);  // the whole sphere
        x.v[i] = w[i].x, y.v[i] = w[i].y, z.v[i] = w[i].z;
      }
      const auto simd = store(sampler.factor(x.load(), y.load(), z.load()));
      for (int i = 0; i < kLanes; ++i) {
        const float scalar = ies_factor(ies, w[i]);
        dark += scalar == 0.0f;
        expect_close(scalar, simd[i], "horizontal table " + table.horizontal);
      }
    }
    EXPECT_GT(dark, 50) << "directions beyond 150 degrees must be tested";
    EXPECT_EQ(store(ies_batch(IesAttachment{}, B(0.0f), B(1.0f), B(0.0f)))[0], 1.0f);
  }
}

}  // namespace
}  // namespace caligo
