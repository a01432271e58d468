#include "lights/sky_generate.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/math.h"

namespace caligo {
namespace {

constexpr RGB kTau{0.08f, 0.14f, 0.30f};        // the air's optical depth towards the zenith
constexpr RGB kZenith{0.20f, 0.38f, 0.85f};     // sky radiance at the zenith, high sun
constexpr RGB kHorizon{0.75f, 0.85f, 1.0f};     // at the horizon
constexpr RGB kGroundAlbedo{0.30f, 0.27f, 0.22f};
constexpr int kSubsamples = 16;  // per pixel side, for the sun disk's coverage

// Kasten & Young (1989): relative optical air mass at an elevation in degrees (38 at 0).
float air_mass(float elevation_degrees) {
  const float e = std::max(elevation_degrees, 0.0f);
  return 1.0f / (std::sin(radians(e)) + 0.50572f * std::pow(e + 6.07995f, -1.6364f));
}

RGB exp_rgb(RGB x) { return {std::exp(x.r), std::exp(x.g), std::exp(x.b)}; }

// The sky without the sun disk: gradient, glow around the sun, ground.
RGB sky_without_disk(Vec3 w, Vec3 sun, RGB sun_colour, float brightness, RGB ground) {
  const float cos_gamma = std::clamp(dot(w, sun), -1.0f, 1.0f);
  const float gamma = std::acos(cos_gamma);
  const float up = std::max(w.y, 0.0f);
  const float t = std::pow(1.0f - up, 4.0f);
  RGB sky = (kZenith * (1.0f - t) + kHorizon * t) * (0.75f * (1.0f + sqr(cos_gamma)) * brightness);
  sky += sun_colour * (brightness * (2.0f * std::exp(-gamma / 0.08f) + 0.4f * std::exp(-gamma / 0.5f)));
  const float above = smoothstep(-0.0175f, 0.0175f, w.y);  // +-1 degree
  return sky * above + ground * (1.0f - above);
}

void check(const SkyParameters& p) {
  if (p.resolution < kMinSkyResolution || p.resolution > kMaxSkyResolution)
    throw std::invalid_argument("sky resolution out of range");
  if (!(p.sun_elevation >= 0.0f && p.sun_elevation <= 90.0f)) throw std::invalid_argument("sun elevation out of range");
  if (!std::isfinite(p.sun_azimuth)) throw std::invalid_argument("sun azimuth is not finite");
  if (!(p.sun_angular_radius >= 0.05f && p.sun_angular_radius <= 10.0f))
    throw std::invalid_argument("sun angular radius out of range");
}

}  // namespace

Vec3 sky_sun_direction(const SkyParameters& p) {
  const float e = radians(p.sun_elevation), a = radians(p.sun_azimuth);
  return {std::sin(a) * std::cos(e), std::sin(e), -std::cos(a) * std::cos(e)};
}

RGB sky_sun_irradiance(const SkyParameters& p) {
  return exp_rgb(kTau * -air_mass(p.sun_elevation)) * kSkySunIrradiance;
}

EnvironmentMap generate_sky(const SkyParameters& p) {
  check(p);
  const int width = p.resolution, height = std::max(1, p.resolution / 2);
  const Vec3 sun = sky_sun_direction(p);
  const RGB sun_e = sky_sun_irradiance(p);
  const RGB sun_colour = sun_e / kSkySunIrradiance;
  const float brightness = 0.15f + 0.85f * smoothstep(0.0f, 0.5f, sun.y);
  // The ground reflects the sun and a sky of mean radiance ~ brightness * 0.5 (Lambertian).
  const RGB ground = kGroundAlbedo * ((sun_e * sun.y + RGB(kPi * 0.5f * brightness)) * kInvPi);

  std::vector<RGB> pixels(size_t(width) * size_t(height));
  std::vector<float> coverage(pixels.size(), 0.0f);
  const float cos_radius = std::cos(radians(p.sun_angular_radius));
  // Pixels whose centre lies within the sun's radius plus a pixel diagonal may be covered.
  const float reach = radians(p.sun_angular_radius) + 2.0f * kPi / float(height);
  double covered_solid_angle = 0.0;
  for (int y = 0; y < height; ++y) {
    const double omega = 2.0 * M_PI / width * (std::cos(M_PI * y / height) - std::cos(M_PI * (y + 1) / height));
    for (int x = 0; x < width; ++x) {
      const Vec2 centre{(float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height)};
      const Vec3 w = latlong_to_direction(centre);
      const size_t i = size_t(y) * size_t(width) + size_t(x);
      pixels[i] = sky_without_disk(w, sun, sun_colour, brightness, ground);
      if (std::acos(std::clamp(dot(w, sun), -1.0f, 1.0f)) > reach) continue;
      int inside = 0;
      for (int sy = 0; sy < kSubsamples; ++sy)
        for (int sx = 0; sx < kSubsamples; ++sx) {
          const Vec2 uv{(float(x) + (float(sx) + 0.5f) / kSubsamples) / float(width),
                        (float(y) + (float(sy) + 0.5f) / kSubsamples) / float(height)};
          if (dot(latlong_to_direction(uv), sun) >= cos_radius) ++inside;
        }
      coverage[i] = float(inside) / float(kSubsamples * kSubsamples);
      covered_solid_angle += coverage[i] * omega;
    }
  }
  // Scale the disk so that sum(L * Omega) over its pixels is the sun's irradiance.
  if (covered_solid_angle > 0.0) {
    const RGB disk = sun_e / float(covered_solid_angle);
    for (size_t i = 0; i < pixels.size(); ++i)
      if (coverage[i] > 0.0f) pixels[i] += disk * coverage[i];
  }
  return EnvironmentMap(width, height, std::move(pixels));
}

}  // namespace caligo
