#include "hybrid/hoffman_preetham.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace caligo {
namespace {

// ∫_{t0}^{t1} e^{-σ t} dt by the midpoint rule in double (exact to ~1e-9 relative at 20000 steps).
double quadrature(double sigma, double t0, double t1) {
  const int n = 20000;
  const double dt = (t1 - t0) / n;
  double sum = 0;
  for (int i = 0; i < n; ++i) sum += std::exp(-sigma * (t0 + (i + 0.5) * dt)) * dt;
  return sum;
}

TEST(HoffmanPreetham, ExtinctionIntegralIsTheQuadraturePerChannel) {
  const RGB sigma(0.02f, 0.7f, 9.0f);
  for (const auto& [t0, t1] : {std::pair{0.0f, 1.0f}, std::pair{0.5f, 3.0f}, std::pair{2.0f, 2.001f}}) {
    const RGB got = extinction_integral(sigma, t0, t1);
    for (int c = 0; c < 3; ++c) {
      const double want = quadrature(sigma[c], t0, t1);
      EXPECT_NEAR(got[c] / want, 1.0, 2e-6) << "channel " << c << " over [" << t0 << ", " << t1 << "]";
    }
  }
}

TEST(HoffmanPreetham, ThinAndEmptyMediaAndEdgeCases) {
  // σ = 0: the length; σ Δ = 1e-7: the length to float precision (no cancellation).
  EXPECT_EQ(extinction_integral(RGB(0.0f), 1.0f, 3.5f).g, 2.5f);
  EXPECT_NEAR(extinction_integral(RGB(1e-7f), 0.0f, 1.0f).r, 1.0f, 1e-6f);
  // Empty or reversed intervals: nothing. Huge optical depths: 0 or 1/σ, never NaN.
  EXPECT_EQ(extinction_integral(RGB(1.0f), 2.0f, 2.0f).r, 0.0f);
  EXPECT_EQ(extinction_integral(RGB(1.0f), 3.0f, 2.0f).r, 0.0f);
  EXPECT_EQ(extinction_integral(RGB(1.0f), 1e6f, 2e6f).r, 0.0f);
  EXPECT_NEAR(extinction_integral(RGB(1e3f), 0.0f, std::numeric_limits<float>::infinity()).b, 1e-3f, 1e-9f);
  // Consecutive steps carry the transmittance: two halves sum to the whole.
  const RGB sigma(0.3f, 1.0f, 2.0f);
  const HoffmanPreethamStep a = hoffman_preetham_step(sigma, RGB(1.0f), 0.7f);
  const HoffmanPreethamStep b = hoffman_preetham_step(sigma, a.end, 0.8f);
  const RGB whole = extinction_integral(sigma, 0.0f, 1.5f);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR((a.integral[c] + b.integral[c]) / whole[c], 1.0, 1e-6);
    EXPECT_NEAR(b.end[c], std::exp(-sigma[c] * 1.5f), 1e-6f);
  }
}

// The sun's case, where the model is exact: a directional light of irradiance E along -z in an
// unbounded medium of constant E (H&P take the sun's attenuated irradiance as given), a view ray
// at 60° to it. L = E σ_s p(θ) (1 - e^{-σ_t s}) / σ_t.
TEST(HoffmanPreetham, ConstantLightGivesTheClosedForm) {
  const ScatteringMedium m{RGB(0.1f, 0.2f, 0.4f), RGB(0.15f, 0.25f, 0.5f), HenyeyGreensteinPhase{0.7f}};
  const Vec3 light_travel(0, 0, -1), to_eye = normalize(Vec3(std::sqrt(3.0f), 0, 1));
  const float p = phase_eval(m.phase, light_travel, to_eye);
  EXPECT_NEAR(p, henyey_greenstein(dot(light_travel, to_eye), 0.7f), 1e-6f);
  const RGB e(2.0f, 1.5f, 1.0f);
  const RGB got = hoffman_preetham_interval(m, e, p, 0.0f, 10.0f);
  for (int c = 0; c < 3; ++c) {
    const double want = e[c] * m.sigma_s[c] * p * quadrature(m.sigma_t[c], 0, 10);
    EXPECT_NEAR(got[c] / want, 1.0, 2e-6);
  }
  EXPECT_TRUE(m.isotropic() == false && m.grey() == false);
  EXPECT_TRUE((ScatteringMedium{RGB(0.1f), RGB(0.2f), HenyeyGreensteinPhase{0.0f}}).isotropic());
  EXPECT_EQ(hoffman_preetham_interval(m, e, -1.0f, 0.0f, 1.0f).r, 0.0f);  // a negative phase reads as 0
}

}  // namespace
}  // namespace caligo
