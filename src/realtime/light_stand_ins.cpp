// Stand-ins for the lights the real-time passes do not shade as they are (light_stand_ins.h).
#include "realtime/light_stand_ins.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "lights/environment_map.h"
#include "lights/ies.h"

namespace caligo {
namespace {

// I(theta) / I(0) of a flat emitter: cos theta on the emitting side (the table ends at 90
// degrees, beyond which a profile gives 0), |cos theta| when two-sided. One-degree steps:
// linear interpolation of cos is then within 4e-5 of it.
std::shared_ptr<const IesProfile> cosine_profile(bool two_sided) {
  const auto build = [](int last) {
    std::vector<float> vertical, values;
    for (int v = 0; v <= last; ++v) {
      vertical.push_back(float(v));
      values.push_back(float(std::abs(std::cos(radians(double(v))))));
    }
    return std::make_shared<const IesProfile>(IesProfile::tabulated(std::move(vertical), {0.0f}, std::move(values)));
  };
  static const std::shared_ptr<const IesProfile> one_sided = build(90), both_sides = build(180);
  return two_sided ? both_sides : one_sided;
}

PointLight flat_stand_in(Vec3 centre, Vec3 area_normal, RGB radiance, bool two_sided) {
  const float area = length(area_normal);
  PointLight p;
  p.position = centre;
  p.intensity = radiance * area;
  p.ies = {cosine_profile(two_sided), area > 0.0f ? area_normal * (1.0f / area) : Vec3{0.0f, 0.0f, 1.0f}};
  return p;
}

}  // namespace

PointLight stand_in(const SphereLight& light) {
  PointLight p;
  p.position = light.center;
  p.intensity = light.radiance * (kPi * sqr(light.radius));
  return p;
}

PointLight stand_in(const QuadLight& light) {
  return flat_stand_in(light.corner + (light.edge1 + light.edge2) * 0.5f, cross(light.edge1, light.edge2),
                       light.radiance, light.two_sided);
}

PointLight stand_in(const DiskLight& light) {
  return flat_stand_in(light.center, light.normal * light.area(), light.radiance, light.two_sided);
}

PointLight stand_in(const TriangleLight& light) {
  return flat_stand_in((light.p0 + light.p1 + light.p2) * (1.0f / 3.0f),
                       cross(light.p1 - light.p0, light.p2 - light.p0) * 0.5f, light.radiance, light.two_sided);
}

namespace {

// The environment as a lat-long grid of radiance times solid angle, with a summed-area table
// of its luminance for the median cuts.
class LatLongEnergy {
 public:
  explicit LatLongEnergy(const EnvironmentLight& light) : light_(light) {
    // A constant sky on a grid fine enough that the cuts' row and column steps leave the
    // parts within ~1 % of equal.
    width_ = light.map ? light.map->width() : 256;
    height_ = light.map ? light.map->height() : 128;
    sat_.assign(size_t(width_ + 1) * size_t(height_ + 1), 0.0);
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x)
        sat_[at(x + 1, y + 1)] = double(energy(x, y).luminance()) + sat_[at(x, y + 1)] + sat_[at(x + 1, y)] -
                                 sat_[at(x, y)];
  }
  int width() const { return width_; }
  int height() const { return height_; }
  // Radiance times the cell's solid angle: what the cell adds to a facing surface's irradiance.
  RGB energy(int x, int y) const {
    const float omega = 2.0f * kPi / float(width_) *
                        float(std::cos(kPi * double(y) / height_) - std::cos(kPi * double(y + 1) / height_));
    return (light_.map ? light_.radiance * light_.map->pixel(x, y) : light_.radiance) * omega;
  }
  double luminance(int x0, int x1, int y0, int y1) const {
    return sat_[at(x1, y1)] - sat_[at(x0, y1)] - sat_[at(x1, y0)] + sat_[at(x0, y0)];
  }
  // The cell centre's direction, in the world (the map turned about +Y).
  Vec3 direction(int x, int y) const {
    const Vec3 m = latlong_to_direction({(float(x) + 0.5f) / float(width_), (float(y) + 0.5f) / float(height_)});
    return {light_.cos_rotation * m.x + light_.sin_rotation * m.z, m.y,
            -light_.sin_rotation * m.x + light_.cos_rotation * m.z};
  }

 private:
  size_t at(int x, int y) const { return size_t(y) * size_t(width_ + 1) + size_t(x); }
  const EnvironmentLight& light_;
  int width_ = 0, height_ = 0;
  std::vector<double> sat_;
};

struct Region {
  int x0, x1, y0, y1;
  double luminance;
  bool splittable() const { return x1 - x0 > 1 || y1 - y0 > 1; }
};

// Cuts `r` across its longer side (in angle: columns shrink by sin(theta) towards the poles)
// where the luminance on either side is closest to half.
std::pair<Region, Region> median_cut(const LatLongEnergy& e, const Region& r) {
  const double theta = kPi * 0.5 * (r.y0 + r.y1) / e.height();
  const double across = 2.0 * kPi * (r.x1 - r.x0) / e.width() * std::sin(theta), down = kPi * (r.y1 - r.y0) / e.height();
  const bool cut_columns = r.x1 - r.x0 > 1 && (across >= down || r.y1 - r.y0 == 1);
  const int lo = cut_columns ? r.x0 : r.y0, hi = cut_columns ? r.x1 : r.y1;
  int best = lo + 1;
  double best_gap = kInfinity;
  for (int k = lo + 1; k < hi; ++k) {
    const double part = cut_columns ? e.luminance(r.x0, k, r.y0, r.y1) : e.luminance(r.x0, r.x1, r.y0, k);
    const double gap = std::abs(part - 0.5 * r.luminance);
    if (gap < best_gap) best_gap = gap, best = k;
  }
  Region a = r, b = r;
  (cut_columns ? a.x1 : a.y1) = best;
  (cut_columns ? b.x0 : b.y0) = best;
  a.luminance = e.luminance(a.x0, a.x1, a.y0, a.y1);
  b.luminance = e.luminance(b.x0, b.x1, b.y0, b.y1);
  return {a, b};
}

EnvironmentSun region_sun(const LatLongEnergy& e, const Region& r, float scene_radius) {
  RGB irradiance(0.0f);
  Vec3 mean{0.0f, 0.0f, 0.0f};
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) {
      const RGB c = e.energy(x, y);
      irradiance += c;
      mean += e.direction(x, y) * c.luminance();
    }
  // |mean| / luminance is the length of the part's mean direction m: a surface that sees all
  // of the part receives irradiance . (n . m), the fog E (isotropic phase).
  const float spread = r.luminance > 0.0 ? float(double(length(mean)) / r.luminance) : 0.0f;
  EnvironmentSun sun;
  // A part spread evenly over the sphere has no mean direction: light from straight above.
  sun.light.direction = spread > 1e-6f ? -normalize(mean) : Vec3{0.0f, -1.0f, 0.0f};
  sun.light.irradiance = irradiance * std::max(spread, 1e-6f);
  sun.light.scene_radius = scene_radius;
  sun.volumetric_scale = 1.0f / std::max(spread, 1e-6f);
  return sun;
}

}  // namespace

std::vector<EnvironmentSun> environment_stand_ins(const EnvironmentLight& light, int count) {
  const LatLongEnergy e(light);
  // The first cut is the horizon (where the grid has one), so that no part straddles it: the
  // sky's parts then light an upward surface exactly.
  std::vector<Region> regions;
  const int horizon = e.height() / 2;
  const auto add = [&](int y0, int y1) {
    if (y1 > y0) regions.push_back({0, e.width(), y0, y1, e.luminance(0, e.width(), y0, y1)});
  };
  if (count >= 2 && e.height() % 2 == 0) {
    add(0, horizon);
    add(horizon, e.height());
  } else {
    add(0, e.height());
  }
  // The brightest part that can still be cut is cut next: parts end with equal shares.
  while (int(regions.size()) < count) {
    auto next = regions.end();
    for (auto it = regions.begin(); it != regions.end(); ++it)
      if (it->splittable() && it->luminance > 0.0 && (next == regions.end() || it->luminance > next->luminance))
        next = it;
    if (next == regions.end()) break;
    const auto [a, b] = median_cut(e, *next);
    *next = a;
    regions.push_back(b);
  }
  std::vector<EnvironmentSun> suns;
  for (const Region& r : regions)
    if (r.luminance > 0.0) suns.push_back(region_sun(e, r, light.scene_radius));
  return suns;
}

}  // namespace caligo
