// The pieces several light types' files share (lights/types/*.cpp): converting area pdfs,
// one-sided emission, sampled points as LightSamples, reach of a whole segment or a range
// sphere, and posing an aimed light. Not part of the lights interface; only the types use it.
#pragma once

#include <optional>

#include "core/ray_range.h"
#include "core/rgb.h"
#include "core/vec.h"
#include "lights/light.h"
#include "lights/light_profile.h"
#include "lights/light_sample.h"

namespace caligo::emitter {

// An area-measure pdf at a light point as solid angle at the receiver.
float area_to_solid_angle(float area_pdf, Vec3 receiver, Vec3 on_light, Vec3 light_normal);

// `radiance` towards w, or black behind a one-sided emitter of normal n.
inline RGB one_sided(RGB radiance, bool two_sided, Vec3 n, Vec3 w) {
  return (two_sided || dot(n, w) > 0.0f) ? radiance : RGB(0.0f);
}

// The point p (normal n) of an emitter of the given area, chosen uniformly by area.
std::optional<LightSample> area_point(Vec3 receiver, Vec3 p, Vec3 n, float area, RGB emitted_towards_receiver);

// A point chosen uniformly in the solid angle `omega` (lights/area_light_sampling.h); the
// receiver is on the emitting side (solid_angle_sampling checked it).
std::optional<LightSample> solid_angle_point(Vec3 receiver, std::optional<Vec3> p, double omega, RGB radiance);

// A delta light's sample: its arrival (lights/light_profile.h, which the real-time passes
// call too) with pdf 1.
std::optional<LightSample> from_arrival(std::optional<DeltaArrival> a);

// The whole of [tmin, tmax]; and the part inside a range sphere (everything for an infinite
// range).
std::optional<RayRange> whole(float tmin, float tmax);
std::optional<RayRange> within_range(Vec3 origin, Vec3 dir, Vec3 centre, float range, float tmin, float tmax);

// The powers only weight the choice of a light, so the IES profile and the gobo enter
// through their means.
float ies_mean(const IesAttachment& ies);
float gobo_mean(const Gobo& gobo);

// Spot and box lights: placed, aimed (up kept a unit vector perpendicular to the new
// direction) and their gobo's scroll and spin folded into offset and rotation.
void pose_aimed_parts(Vec3& position, Vec3& direction, Vec3& up, Gobo& gobo, const LightPose& at);
template <typename Aimed>
void pose_aimed(Aimed& l, const LightPose& at) {
  pose_aimed_parts(l.position, l.direction, l.up, l.gobo, at);
}

}  // namespace caligo::emitter
