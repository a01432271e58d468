#include "lights/area_light_sampling.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/math.h"
#include "lights/spherical_sampling.h"

namespace caligo {
namespace {

constexpr unsigned kAreaBit = 1u, kUnclippedBit = 2u;

unsigned encode(LightSamplingOptions o) {
  return (o.solid_angle ? 0u : kAreaBit) | (o.clip_equiangular ? 0u : kUnclippedBit);
}

// CALIGO_LIGHT_SAMPLING, parsed before main: a typo must not silently benchmark the default.
unsigned options_from_environment() {
  LightSamplingOptions o;
  const char* value = std::getenv("CALIGO_LIGHT_SAMPLING");
  if (!value) return encode(o);
  const std::string text = value;
  size_t begin = 0;
  while (begin <= text.size()) {
    const size_t end = std::min(text.find(',', begin), text.size());
    const std::string word = text.substr(begin, end - begin);
    if (word == "area") o.solid_angle = false;
    else if (word == "solid-angle") o.solid_angle = true;
    else if (word == "unclipped") o.clip_equiangular = false;
    else if (word == "clipped") o.clip_equiangular = true;
    else if (!word.empty()) {
      std::fprintf(stderr,
                   "caligo: CALIGO_LIGHT_SAMPLING: unknown word \"%s\" (expected a comma-separated list of "
                   "area, solid-angle, unclipped, clipped)\n",
                   word.c_str());
      std::exit(2);
    }
    begin = end + 1;
  }
  return encode(o);
}

std::atomic<unsigned> g_options{options_from_environment()};

bool in_stable_range(double omega) { return omega >= kMinSolidAngle && omega <= kMaxSolidAngle; }

// Beyond kFarRadii bounding radii from the light's centre (see the header).

bool far_from(Vec3 receiver, Vec3 centre, float radius) {
  return length_squared(receiver - centre) > sqr(float(kFarRadii) * radius);
}

bool is_rectangle(const QuadLight& l) {
  return std::abs(dot(l.edge1, l.edge2)) <= 1e-5f * length(l.edge1) * length(l.edge2);
}

// Whether `receiver` is on the side the light emits towards.
bool receives(Vec3 receiver, Vec3 on_plane, Vec3 normal, bool two_sided) {
  const float side = dot(normal, receiver - on_plane);
  return two_sided ? side != 0.0f : side > 0.0f;
}

}  // namespace

LightSamplingOptions light_sampling_options() {
  const unsigned bits = g_options.load(std::memory_order_relaxed);
  return {(bits & kAreaBit) == 0, (bits & kUnclippedBit) == 0};
}

void set_light_sampling_options(LightSamplingOptions options) {
  g_options.store(encode(options), std::memory_order_relaxed);
}

namespace {

SolidAngleSampling quad_setup(const QuadLight& l, Vec3 receiver) {
  SolidAngleSampling s;
  s.rectangle = is_rectangle(l);
  if (s.rectangle) {
    s.rect = make_spherical_rectangle(receiver, l.corner, l.edge1, l.edge2);
    s.solid_angle = s.rect.solid_angle;
    return s;
  }
  const Vec3 far = l.corner + l.edge1 + l.edge2;
  s.tri[0] = make_spherical_triangle(receiver, l.corner, l.corner + l.edge1, far);
  s.tri[1] = make_spherical_triangle(receiver, l.corner, far, l.corner + l.edge2);
  s.solid_angle = s.tri[0].solid_angle + s.tri[1].solid_angle;
  return s;
}

SolidAngleSampling in_range(SolidAngleSampling s) {
  if (!in_stable_range(s.solid_angle)) s.solid_angle = 0.0;
  return s;
}

}  // namespace

double quad_solid_angle(const QuadLight& l, Vec3 receiver) { return quad_setup(l, receiver).solid_angle; }

SolidAngleSampling solid_angle_sampling(const QuadLight& l, Vec3 receiver) {
  if (!light_sampling_options().solid_angle) return {};
  if (!receives(receiver, l.corner, cross(l.edge1, l.edge2), l.two_sided)) return {};
  const Vec3 half_diagonal = (l.edge1 + l.edge2) * 0.5f;
  if (far_from(receiver, l.corner + half_diagonal, std::max(length(half_diagonal), length(l.edge1 - l.edge2) * 0.5f)))
    return {};
  return in_range(quad_setup(l, receiver));
}

SolidAngleSampling solid_angle_sampling(const TriangleLight& l, Vec3 receiver) {
  if (!light_sampling_options().solid_angle) return {};
  if (!receives(receiver, l.p0, cross(l.p1 - l.p0, l.p2 - l.p0), l.two_sided)) return {};
  const Vec3 centre = (l.p0 + l.p1 + l.p2) / 3.0f;
  if (far_from(receiver, centre,
               std::sqrt(std::max({length_squared(l.p0 - centre), length_squared(l.p1 - centre),
                                   length_squared(l.p2 - centre)}))))
    return {};
  SolidAngleSampling s;
  s.tri[0] = make_spherical_triangle(receiver, l.p0, l.p1, l.p2);
  s.solid_angle = s.tri[0].solid_angle;
  return in_range(s);
}

std::optional<Vec3> sample_solid_angle(const SolidAngleSampling& s, Vec2 u) {
  if (s.rectangle) return sample_spherical_rectangle(s.rect, u);
  if (s.tri[1].solid_angle <= 0.0) return sample_spherical_triangle(s.tri[0], u);
  // A parallelogram: one of its two triangles in proportion to solid angle, u.x reused.
  const float p_first = float(s.tri[0].solid_angle / s.solid_angle);
  if (u.x < p_first) return sample_spherical_triangle(s.tri[0], {u.x / p_first, u.y});
  const float rest = std::min((u.x - p_first) / (1.0f - p_first), kOneMinusEpsilon);
  return sample_spherical_triangle(s.tri[1], {rest, u.y});
}

}  // namespace caligo
