// The functions over `Light`: each dispatches to the type's member (lights/types/*.cpp).
// The Emitter concept states the interface CALIGO_EMITTER declares, so that a type missing a
// member fails here, once, with the member's name.
#include "lights/light.h"

#include <concepts>

#include "lights/light_reach.h"
#include "lights/light_sample.h"
#include "lights/light_tree.h"

namespace caligo {
namespace {

template <typename T>
concept Emitter = requires(T& mutable_light, const T& l, Vec3 v, Vec2 u, float t) {
  { T::kTypeName } -> std::convertible_to<const char*>;
  { T::kInfinite } -> std::convertible_to<bool>;
  { l.is_delta() } -> std::same_as<bool>;
  { l.power() } -> std::same_as<float>;
  { l.centre() } -> std::same_as<std::optional<Vec3>>;
  { mutable_light.pose(LightPose{}) } -> std::same_as<void>;
  { l.sample(v, u) } -> std::same_as<std::optional<LightSample>>;
  { l.pdf(v, v, v, v) } -> std::same_as<float>;
  { l.escaped(v) } -> std::same_as<RGB>;
  { l.reach(v, v, t, t) } -> std::same_as<std::optional<RayRange>>;
  { l.bounds() } -> std::same_as<std::optional<LightBounds>>;
  { l.surface() } -> std::same_as<std::optional<LightGeometry>>;
};

template <typename... Types>
constexpr bool all_emitters(const std::variant<Types...>*) {
  return (Emitter<Types> && ...);
}
static_assert(all_emitters(static_cast<const Light*>(nullptr)),
              "every member of Light declares CALIGO_EMITTER (lights/light.h)");

// Lights at infinity hold the scene's radius, for their power.
struct SetSceneRadius {
  float radius;
  template <typename T>
  void operator()(T& l) const {
    if constexpr (T::kInfinite) l.scene_radius = radius;
  }
};

}  // namespace

void pose_light(Light& light, const LightPose& at) {
  std::visit([&](auto& l) { l.pose(at); }, light);
}
void set_scene_radius(Light& light, float radius) { std::visit(SetSceneRadius{radius}, light); }
std::optional<Vec3> light_centre(const Light& light) {
  return std::visit([](const auto& l) { return l.centre(); }, light);
}
const char* light_type_name(const Light& light) {
  return std::visit([](const auto& l) { return std::decay_t<decltype(l)>::kTypeName; }, light);
}
bool is_delta(const Light& light) {
  return std::visit([](const auto& l) { return l.is_delta(); }, light);
}
bool is_infinite(const Light& light) {
  return std::visit([](const auto& l) { return std::decay_t<decltype(l)>::kInfinite; }, light);
}
float power(const Light& light) {
  return std::visit([](const auto& l) { return l.power(); }, light);
}
std::optional<LightGeometry> visible_geometry(const Light& light) {
  return std::visit([](const auto& l) { return l.surface(); }, light);
}

std::optional<LightSample> sample_light(const Light& light, Vec3 receiver, Vec2 u) {
  return std::visit([&](const auto& l) { return l.sample(receiver, u); }, light);
}
float light_pdf(const Light& light, Vec3 receiver, Vec3 wi, Vec3 on_light, Vec3 light_normal) {
  return std::visit([&](const auto& l) { return l.pdf(receiver, wi, on_light, light_normal); }, light);
}
RGB escaped_radiance(const Light& light, Vec3 w) {
  return std::visit([&](const auto& l) { return l.escaped(w); }, light);
}

std::optional<LightBounds> light_bounds(const Light& light) {
  return std::visit([](const auto& l) { return l.bounds(); }, light);
}

}  // namespace caligo
