#include "materials/bsdf.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/math.h"
#include "core/rng.h"
#include "core/sampling.h"

namespace caligo {
namespace {

TEST(Diffuse, EvalPdfAndSampleAgree) {
  const DiffuseBsdf diffuse{RGB(0.6f, 0.5f, 0.4f)};
  const Bsdf bsdf = diffuse;
  const Vec3 n = normalize(Vec3(0.2f, 1, 0.1f));
  const Vec3 wo = normalize(Vec3(-0.5f, 1, 0.3f));
  Pcg32 rng(1, 2);
  double pdf_integral = 0.0;
  const int kCount = 100000;
  for (int i = 0; i < kCount; ++i) {
    const auto s = bsdf_sample(bsdf, n, wo, rng.next_float(), {rng.next_float(), rng.next_float()});
    ASSERT_TRUE(s);
    EXPECT_GT(dot(s->wi, n), 0.0f);
    EXPECT_NEAR(s->pdf, bsdf_pdf(bsdf, n, wo, s->wi), 1e-4f);
    const RGB expected_weight = bsdf_eval(bsdf, n, wo, s->wi) * abs_dot(n, s->wi) / s->pdf;
    EXPECT_NEAR(s->weight.r, expected_weight.r, 1e-3f);
    // Integrate the pdf with uniform sphere samples.
    const Vec3 w = sample_uniform_sphere({rng.next_float(), rng.next_float()});
    pdf_integral += bsdf_pdf(bsdf, n, wo, w) / uniform_sphere_pdf();
  }
  EXPECT_NEAR(pdf_integral / kCount, 1.0, 0.01);
  EXPECT_FLOAT_EQ(bsdf_eval(bsdf, n, wo, wo).g, 0.5f * kInvPi);
  EXPECT_TRUE(bsdf_eval(bsdf, n, wo, -wo).is_black());  // no transmission
}

TEST(Diffuse, ReflectsFromTheBackSideToo) {
  const Bsdf bsdf = DiffuseBsdf{RGB(0.5f)};
  const auto s = bsdf_sample(bsdf, {0, 0, 1}, {0, 0, -1}, 0.5f, {0.3f, 0.6f});
  ASSERT_TRUE(s);
  EXPECT_LT(s->wi.z, 0.0f);
}

TEST(Fresnel, KnownValues) {
  EXPECT_NEAR(fresnel_dielectric(1.0f, 1.5f), 0.04f, 1e-6f);
  EXPECT_NEAR(fresnel_dielectric(-1.0f, 1.5f), 0.04f, 1e-6f);
  EXPECT_NEAR(fresnel_dielectric(0.0f, 1.5f), 1.0f, 1e-6f);
  // Inside glass beyond the critical angle asin(1/1.5) = 41.8 degrees: total internal reflection.
  EXPECT_FLOAT_EQ(fresnel_dielectric(-std::cos(radians(45.0f)), 1.5f), 1.0f);
  EXPECT_LT(fresnel_dielectric(-std::cos(radians(40.0f)), 1.5f), 1.0f);
}

TEST(Dielectric, RefractionObeysSnell) {
  const Bsdf glass = DielectricBsdf{1.5f};
  const Vec3 n(0, 0, 1);
  const float theta_i = radians(50.0f);
  const Vec3 wo(std::sin(theta_i), 0, std::cos(theta_i));
  // u_lobe = 0.99 > F: transmission.
  const auto s = bsdf_sample(glass, n, wo, 0.99f, {});
  ASSERT_TRUE(s);
  EXPECT_TRUE(s->specular);
  EXPECT_LT(s->wi.z, 0.0f);
  const float sin_t = std::sqrt(sqr(s->wi.x) + sqr(s->wi.y));
  EXPECT_NEAR(std::sin(theta_i), 1.5f * sin_t, 1e-5f);
  EXPECT_NEAR(s->wi.x, -sin_t, 1e-6f);  // continues across the normal
  EXPECT_NEAR(s->weight.r, 1.0f / 2.25f, 1e-6f);
  // u_lobe = 0 < F: mirror reflection.
  const auto r = bsdf_sample(glass, n, wo, 0.0f, {});
  ASSERT_TRUE(r);
  EXPECT_NEAR(r->wi.x, -wo.x, 1e-6f);
  EXPECT_NEAR(r->wi.z, wo.z, 1e-6f);
}

TEST(Dielectric, ReflectionProbabilityIsFresnel) {
  const Bsdf glass = DielectricBsdf{1.33f};
  const Vec3 n(0, 0, 1), wo = normalize(Vec3(0.8f, 0, 0.3f));
  Pcg32 rng(5, 6);
  int reflected = 0;
  const int kCount = 200000;
  for (int i = 0; i < kCount; ++i) {
    const auto s = bsdf_sample(glass, n, wo, rng.next_float(), {});
    if (s && s->wi.z > 0) ++reflected;
  }
  const float f = fresnel_dielectric(wo.z, 1.33f);
  EXPECT_NEAR(double(reflected) / kCount, f, 4.0 * std::sqrt(f * (1 - f) / kCount));
}

TEST(NullAndBlack, PassThroughAndAbsorb) {
  const auto s = bsdf_sample(NullBsdf{}, {0, 0, 1}, {0.6f, 0, 0.8f}, 0.5f, {});
  ASSERT_TRUE(s);
  EXPECT_FLOAT_EQ(s->wi.x, -0.6f);
  EXPECT_FALSE(bsdf_sample(BlackBsdf{}, {0, 0, 1}, {0, 0, 1}, 0.5f, {0.5f, 0.5f}));
  EXPECT_TRUE(is_specular(NullBsdf{}));
  EXPECT_FALSE(is_specular(DiffuseBsdf{}));
}

}  // namespace
}  // namespace caligo
