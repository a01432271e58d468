#include "lights/light.h"

#include <cmath>

#include "core/math.h"

namespace caligo {
namespace {

struct IsDelta {
  bool operator()(const PointLight&) const { return true; }
  bool operator()(const SpotLight&) const { return true; }
  bool operator()(const DirectionalLight& l) const { return l.cos_angular_radius >= 1.0f; }
  bool operator()(const auto&) const { return false; }
};

struct IsInfinite {
  bool operator()(const DirectionalLight&) const { return true; }
  bool operator()(const EnvironmentLight&) const { return true; }
  bool operator()(const auto&) const { return false; }
};

float parallelogram_area(Vec3 e1, Vec3 e2) { return length(cross(e1, e2)); }

struct Power {
  float operator()(const PointLight& l) const { return 4.0f * kPi * l.intensity.average(); }
  // The smoothstep falloff integrates to the cone midway between inner and outer (pbrt-v4's
  // approximation; exact for a linear ramp in cos theta).
  float operator()(const SpotLight& l) const {
    return 2.0f * kPi * (1.0f - 0.5f * (l.cos_inner + l.cos_outer)) * l.intensity.average();
  }
  float operator()(const SphereLight& l) const {
    return (l.two_sided ? 2.0f : 1.0f) * kPi * 4.0f * kPi * sqr(l.radius) * l.radiance.average();
  }
  float operator()(const QuadLight& l) const {
    return (l.two_sided ? 2.0f : 1.0f) * kPi * parallelogram_area(l.edge1, l.edge2) * l.radiance.average();
  }
  float operator()(const DirectionalLight& l) const {
    return kPi * sqr(l.scene_radius) * l.irradiance.average();
  }
  float operator()(const EnvironmentLight& l) const {
    return 4.0f * kPi * kPi * sqr(l.scene_radius) * l.radiance.average();
  }
  float operator()(const TriangleLight& l) const {
    return (l.two_sided ? 2.0f : 1.0f) * kPi * 0.5f * parallelogram_area(l.p1 - l.p0, l.p2 - l.p0) *
           l.radiance.average();
  }
};

}  // namespace

bool is_delta(const Light& light) { return std::visit(IsDelta{}, light); }
bool is_infinite(const Light& light) { return std::visit(IsInfinite{}, light); }
float power(const Light& light) { return std::visit(Power{}, light); }

}  // namespace caligo
