#include "lights/light.h"

#include <cmath>

#include "core/math.h"
#include "lights/environment_map.h"
#include "lights/gobo.h"
#include "lights/ies.h"

namespace caligo {
namespace {

struct IsDelta {
  bool operator()(const PointLight&) const { return true; }
  bool operator()(const SpotLight&) const { return true; }
  bool operator()(const BoxLight&) const { return true; }
  bool operator()(const DirectionalLight& l) const { return l.cos_angular_radius >= 1.0f; }
  bool operator()(const SphereLight&) const { return false; }
  bool operator()(const QuadLight&) const { return false; }
  bool operator()(const TriangleLight&) const { return false; }
  bool operator()(const EnvironmentLight&) const { return false; }
};

// A box light is parallel light but bounded: its rays start on a face in the scene, so it
// is not "at infinity" (no escaped radiance, finite shadow rays).
struct IsInfinite {
  bool operator()(const DirectionalLight&) const { return true; }
  bool operator()(const EnvironmentLight&) const { return true; }
  bool operator()(const PointLight&) const { return false; }
  bool operator()(const SpotLight&) const { return false; }
  bool operator()(const BoxLight&) const { return false; }
  bool operator()(const SphereLight&) const { return false; }
  bool operator()(const QuadLight&) const { return false; }
  bool operator()(const TriangleLight&) const { return false; }
};

float ies_mean(const IesAttachment& ies) { return ies.profile ? ies.profile->mean() : 1.0f; }
float gobo_mean(const Gobo& gobo) { return gobo.image ? gobo.image->mean().average() : 1.0f; }

float parallelogram_area(Vec3 e1, Vec3 e2) { return length(cross(e1, e2)); }

struct Power {
  // Powers here only weight the choice of a light, so range windows are ignored and the IES
  // profile and gobo enter through their means (for a spot, an approximation: the profile's
  // mean over the sphere is not its mean over the cone).
  float operator()(const PointLight& l) const { return 4.0f * kPi * l.intensity.average() * ies_mean(l.ies); }
  // The smoothstep falloff integrates to the cone midway (in cos theta) between inner and
  // outer: exact, as smoothstep integrates to 1/2 over its ramp (light_test.cpp checks it).
  float operator()(const SpotLight& l) const {
    return 2.0f * kPi * (1.0f - 0.5f * (l.cos_inner + l.cos_outer)) * l.intensity.average() *
           ies_mean(l.ies) * gobo_mean(l.gobo);
  }
  // Irradiance times the emitting face's area.
  float operator()(const BoxLight& l) const {
    return 4.0f * l.half_width * l.half_height * l.irradiance.average() * gobo_mean(l.gobo);
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
  // pi r^2 times the radiance integrated over the sphere (4 pi L for a constant one).
  float operator()(const EnvironmentLight& l) const {
    const RGB integral = l.map ? l.radiance * l.map->integral() : l.radiance * (4.0f * kPi);
    return kPi * sqr(l.scene_radius) * integral.average();
  }
  float operator()(const TriangleLight& l) const {
    return (l.two_sided ? 2.0f : 1.0f) * kPi * 0.5f * parallelogram_area(l.p1 - l.p0, l.p2 - l.p0) *
           l.radiance.average();
  }
};

struct LightCentre {
  std::optional<Vec3> operator()(const PointLight& l) const { return l.position; }
  std::optional<Vec3> operator()(const SpotLight& l) const { return l.position; }
  std::optional<Vec3> operator()(const SphereLight& l) const { return l.center; }
  std::optional<Vec3> operator()(const QuadLight& l) const { return l.corner + (l.edge1 + l.edge2) * 0.5f; }
  std::optional<Vec3> operator()(const TriangleLight& l) const { return (l.p0 + l.p1 + l.p2) / 3.0f; }
  std::optional<Vec3> operator()(const BoxLight&) const { return std::nullopt; }
  std::optional<Vec3> operator()(const DirectionalLight&) const { return std::nullopt; }
  std::optional<Vec3> operator()(const EnvironmentLight&) const { return std::nullopt; }
};

struct TypeName {
  const char* operator()(const PointLight&) const { return "point"; }
  const char* operator()(const SpotLight&) const { return "spot"; }
  const char* operator()(const SphereLight&) const { return "sphere"; }
  const char* operator()(const QuadLight&) const { return "quad"; }
  const char* operator()(const DirectionalLight&) const { return "directional"; }
  const char* operator()(const EnvironmentLight&) const { return "environment"; }
  const char* operator()(const TriangleLight&) const { return "triangle"; }
  const char* operator()(const BoxLight&) const { return "box"; }
};

// Keeps `up` a unit vector perpendicular to `direction` (Gram-Schmidt), falling back to any
// perpendicular when the new direction is parallel to the old up.
Vec3 orthogonal_up(Vec3 up, Vec3 direction) {
  const Vec3 u = up - direction * dot(up, direction);
  if (length_squared(u) > 1e-8f) return normalize(u);
  return Frame::from_z(direction).t;
}

void advance(Gobo& gobo, float time) {
  gobo.offset = {gobo.offset.x + gobo.scroll.x * time, gobo.offset.y + gobo.scroll.y * time};
  gobo.rotation += gobo.spin * time;
  gobo.scroll = {};
  gobo.spin = 0.0f;
}

struct PoseLight {
  std::optional<Vec3> position, direction;
  float time;

  void operator()(PointLight& l) const {
    if (position) l.position = *position;
  }
  // Spot and box lights: placed, aimed (up kept perpendicular) and their gobo advanced.
  template <typename Aimed>
  void aim(Aimed& l) const {
    if (position) l.position = *position;
    if (direction) {
      l.direction = *direction;
      l.up = orthogonal_up(l.up, l.direction);
    }
    advance(l.gobo, time);
  }
  void operator()(SpotLight& l) const { aim(l); }
  void operator()(BoxLight& l) const { aim(l); }
  void operator()(DirectionalLight& l) const {
    if (direction) l.direction = *direction;
  }
  void operator()(SphereLight&) const {}
  void operator()(QuadLight&) const {}
  void operator()(TriangleLight&) const {}
  void operator()(EnvironmentLight&) const {}
};

struct SetSceneRadius {
  float radius;
  void operator()(DirectionalLight& l) const { l.scene_radius = radius; }
  void operator()(EnvironmentLight& l) const { l.scene_radius = radius; }
  void operator()(PointLight&) const {}
  void operator()(SpotLight&) const {}
  void operator()(BoxLight&) const {}
  void operator()(SphereLight&) const {}
  void operator()(QuadLight&) const {}
  void operator()(TriangleLight&) const {}
};

}  // namespace

void pose_light(Light& light, std::optional<Vec3> position, std::optional<Vec3> direction, float time) {
  std::visit(PoseLight{position, direction, time}, light);
}
void set_scene_radius(Light& light, float radius) { std::visit(SetSceneRadius{radius}, light); }
std::optional<Vec3> light_centre(const Light& light) { return std::visit(LightCentre{}, light); }
const char* light_type_name(const Light& light) { return std::visit(TypeName{}, light); }
bool is_delta(const Light& light) { return std::visit(IsDelta{}, light); }
bool is_infinite(const Light& light) { return std::visit(IsInfinite{}, light); }
float power(const Light& light) { return std::visit(Power{}, light); }

}  // namespace caligo
