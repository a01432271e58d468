#include "lights/light_sample.h"

#include <cmath>

#include "core/math.h"
#include "core/sampling.h"
#include "lights/area_light_sampling.h"
#include "lights/environment_map.h"
#include "lights/light_profile.h"

namespace caligo {
namespace {

// Converts an area-measure pdf at a light point into solid angle at the receiver.
float area_to_solid_angle(float area_pdf, Vec3 receiver, Vec3 on_light, Vec3 light_normal) {
  const Vec3 d = on_light - receiver;
  const float dist2 = length_squared(d);
  const float cos_light = std::abs(dot(light_normal, d)) / std::sqrt(dist2);
  if (cos_light <= 0.0f) return 0.0f;
  return area_pdf * dist2 / cos_light;
}

RGB one_sided(RGB radiance, bool two_sided, Vec3 n, Vec3 w) {
  return (two_sided || dot(n, w) > 0.0f) ? radiance : RGB(0.0f);
}

std::optional<LightSample> sample_area_point(Vec3 receiver, Vec3 p, Vec3 n, float area,
                                             RGB emitted_towards_receiver) {
  const Vec3 d = p - receiver;
  const float dist = length(d);
  if (!(dist > 0.0f) || emitted_towards_receiver.is_black()) return std::nullopt;
  const Vec3 wi = d / dist;
  const float pdf = area_to_solid_angle(1.0f / area, receiver, p, n);
  if (!(pdf > 0.0f) || !std::isfinite(pdf)) return std::nullopt;
  return LightSample{emitted_towards_receiver, wi, dist, pdf, false};
}

// A point chosen uniformly in the solid angle `omega` (lights/area_light_sampling.h); the
// receiver is on the emitting side (solid_angle_sampling checked it).
std::optional<LightSample> sample_solid_angle_point(Vec3 receiver, std::optional<Vec3> p, double omega,
                                                    RGB radiance) {
  if (!p || radiance.is_black()) return std::nullopt;
  const Vec3 d = *p - receiver;
  const float dist = length(d);
  if (!(dist > 0.0f)) return std::nullopt;
  return LightSample{radiance, d / dist, dist, float(1.0 / omega), false};
}

// An environment map's frame from the world's and back: R_y(-angle) and R_y(angle).
Vec3 environment_to_map(const EnvironmentLight& l, Vec3 w) {
  return {l.cos_rotation * w.x - l.sin_rotation * w.z, w.y, l.sin_rotation * w.x + l.cos_rotation * w.z};
}
Vec3 environment_to_world(const EnvironmentLight& l, Vec3 m) {
  return {l.cos_rotation * m.x + l.sin_rotation * m.z, m.y, -l.sin_rotation * m.x + l.cos_rotation * m.z};
}

// Delta lights go through delta_arrival, the function the real-time passes call too.
std::optional<LightSample> from_arrival(std::optional<DeltaArrival> a) {
  if (!a) return std::nullopt;
  return LightSample{a->radiance, a->wi, a->distance, 1.0f, true};
}

// Uniform cone sampling of the directions a sphere subtends; from inside, uniform area sampling.
std::optional<LightSample> sample_sphere(const SphereLight& l, Vec3 receiver, Vec2 u) {
  const Vec3 to_center = l.center - receiver;
  const float dist2 = length_squared(to_center);
  const float r2 = sqr(l.radius);
  if (dist2 <= r2 * 1.0001f) {
    const Vec3 n = sample_uniform_sphere(u);
    const Vec3 p = l.center + n * l.radius;
    return sample_area_point(receiver, p, n, 4.0f * kPi * r2,
                             one_sided(l.radiance, l.two_sided, n, receiver - p));
  }
  const float dist = std::sqrt(dist2);
  const float sin2_max = r2 / dist2;
  const float cos_max = safe_sqrt(1.0f - sin2_max);
  if (l.radiance.is_black()) return std::nullopt;
  const Frame frame = Frame::from_z(to_center / dist);
  const Vec3 wi = frame.to_world(sample_uniform_cone(u, cos_max));
  // Distance to the near intersection of the sampled direction with the sphere.
  const float b = dot(wi, to_center);
  const float t = b - safe_sqrt(r2 - (dist2 - b * b));
  return LightSample{l.radiance, wi, t, uniform_cone_pdf(cos_max), false};
}

struct Sample {
  Vec3 receiver;
  Vec2 u;

  std::optional<LightSample> operator()(const PointLight& l) const {
    return from_arrival(delta_arrival(l, receiver));
  }
  std::optional<LightSample> operator()(const SpotLight& l) const {
    return from_arrival(delta_arrival(l, receiver));
  }
  // The shadow ray ends on the emitting face (distance = depth inside the box).
  std::optional<LightSample> operator()(const BoxLight& l) const {
    return from_arrival(delta_arrival(l, receiver));
  }
  std::optional<LightSample> operator()(const SphereLight& l) const { return sample_sphere(l, receiver, u); }
  std::optional<LightSample> operator()(const QuadLight& l) const {
    if (const SolidAngleSampling s = solid_angle_sampling(l, receiver); s.solid_angle > 0.0)
      return sample_solid_angle_point(receiver, sample_solid_angle(s, u), s.solid_angle, l.radiance);
    const Vec3 p = l.corner + l.edge1 * u.x + l.edge2 * u.y;
    const Vec3 c = cross(l.edge1, l.edge2);
    const float area = length(c);
    const Vec3 n = c / area;
    return sample_area_point(receiver, p, n, area, one_sided(l.radiance, l.two_sided, n, receiver - p));
  }
  std::optional<LightSample> operator()(const TriangleLight& l) const {
    if (const SolidAngleSampling s = solid_angle_sampling(l, receiver); s.solid_angle > 0.0)
      return sample_solid_angle_point(receiver, sample_solid_angle(s, u), s.solid_angle, l.radiance);
    const Vec3 b = sample_uniform_triangle(u);
    const Vec3 p = l.p0 * b.x + l.p1 * b.y + l.p2 * b.z;
    const Vec3 c = cross(l.p1 - l.p0, l.p2 - l.p0);
    const float area = 0.5f * length(c);
    const Vec3 n = normalize(c);
    return sample_area_point(receiver, p, n, area, one_sided(l.radiance, l.two_sided, n, receiver - p));
  }
  std::optional<LightSample> operator()(const DirectionalLight& l) const {
    const Vec3 towards = -l.direction;
    if (l.cos_angular_radius >= 1.0f) return LightSample{l.irradiance, towards, kInfinity, 1.0f, true};
    const Vec3 wi = Frame::from_z(towards).to_world(sample_uniform_cone(u, l.cos_angular_radius));
    return LightSample{escaped_radiance(l, wi), wi, kInfinity, uniform_cone_pdf(l.cos_angular_radius), false};
  }
  // A constant environment uniformly over the sphere; a map by its own distribution.
  std::optional<LightSample> operator()(const EnvironmentLight& l) const {
    if (!l.map) return LightSample{l.radiance, sample_uniform_sphere(u), kInfinity, uniform_sphere_pdf(), false};
    const auto s = l.map->sample(u);
    if (!s) return std::nullopt;
    return LightSample{l.radiance * l.map->lookup(s->w), environment_to_world(l, s->w), kInfinity, s->pdf, false};
  }
};

struct Pdf {
  Vec3 receiver, wi, on_light, light_normal;

  float operator()(const PointLight&) const { return 0.0f; }
  float operator()(const SpotLight&) const { return 0.0f; }
  float operator()(const BoxLight&) const { return 0.0f; }
  float operator()(const SphereLight& l) const {
    const float dist2 = length_squared(l.center - receiver);
    const float r2 = sqr(l.radius);
    if (dist2 <= r2 * 1.0001f)
      return area_to_solid_angle(1.0f / (4.0f * kPi * r2), receiver, on_light, light_normal);
    return uniform_cone_pdf(safe_sqrt(1.0f - r2 / dist2));
  }
  float operator()(const QuadLight& l) const {
    if (const double omega = solid_angle_sampling(l, receiver).solid_angle; omega > 0.0) return float(1.0 / omega);
    return area_to_solid_angle(1.0f / length(cross(l.edge1, l.edge2)), receiver, on_light, light_normal);
  }
  float operator()(const TriangleLight& l) const {
    if (const double omega = solid_angle_sampling(l, receiver).solid_angle; omega > 0.0) return float(1.0 / omega);
    return area_to_solid_angle(1.0f / (0.5f * length(cross(l.p1 - l.p0, l.p2 - l.p0))), receiver, on_light,
                               light_normal);
  }
  float operator()(const DirectionalLight& l) const {
    if (l.cos_angular_radius >= 1.0f || dot(-l.direction, wi) < l.cos_angular_radius) return 0.0f;
    return uniform_cone_pdf(l.cos_angular_radius);
  }
  float operator()(const EnvironmentLight& l) const {
    return l.map ? l.map->pdf(environment_to_map(l, wi)) : uniform_sphere_pdf();
  }
};

// A sun of irradiance E and angular radius a has uniform radiance E / (pi sin^2 a) over its
// disk: the cosine-weighted solid angle of a cone of half-angle a is pi sin^2 a.
RGB sun_radiance(const DirectionalLight& l) {
  const float sin2 = 1.0f - sqr(l.cos_angular_radius);
  return l.irradiance / (kPi * sin2);
}

// Only lights at infinity are seen by rays leaving the scene; a delta sun cannot be hit.
struct Escaped {
  Vec3 w;

  RGB operator()(const EnvironmentLight& l) const {
    return l.map ? l.radiance * l.map->lookup(environment_to_map(l, w)) : l.radiance;
  }
  RGB operator()(const DirectionalLight& l) const {
    if (l.cos_angular_radius >= 1.0f || dot(-l.direction, w) < l.cos_angular_radius) return RGB(0.0f);
    return sun_radiance(l);
  }
  RGB operator()(const PointLight&) const { return RGB(0.0f); }
  RGB operator()(const SpotLight&) const { return RGB(0.0f); }
  RGB operator()(const BoxLight&) const { return RGB(0.0f); }
  RGB operator()(const SphereLight&) const { return RGB(0.0f); }
  RGB operator()(const QuadLight&) const { return RGB(0.0f); }
  RGB operator()(const TriangleLight&) const { return RGB(0.0f); }
};

}  // namespace

std::optional<LightSample> sample_light(const Light& light, Vec3 receiver, Vec2 u) {
  return std::visit(Sample{receiver, u}, light);
}

float light_pdf(const Light& light, Vec3 receiver, Vec3 wi, Vec3 on_light, Vec3 light_normal) {
  return std::visit(Pdf{receiver, wi, on_light, light_normal}, light);
}

RGB escaped_radiance(const Light& light, Vec3 w) { return std::visit(Escaped{w}, light); }

}  // namespace caligo
