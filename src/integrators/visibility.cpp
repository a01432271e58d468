#include "integrators/visibility.h"

#include <algorithm>
#include <cmath>
#include <variant>

#include "integrators/path_tracer.h"
#include "raymarch/march.h"
#include "tracking/tracking.h"

namespace caligo {

// Shadow rays stop this fraction short of an area-light sample so they do not hit the light.
constexpr float kShadowEpsilon = 1e-4f;

namespace {

// One stretch of a shadow ray through the volumes (and the stack's medium), by the shadow medium's
// estimator; `rng` is the ray's generator, used only when tracking.
RGB stretch_transmittance(const Scene& scene, const Ray& stretch, const ShadowMedium& medium, int stack_medium,
                          PathScratch& scratch, Pcg32& rng) {
  const MarchSettings& settings = scratch.march_settings;
  if (medium.policy == SecondarySegments::kMarch)
    return march_transmittance(scene.volumes(), stretch, medium.jitter, settings, scratch.march, stack_medium);
  // The coarse spans decide (a tracked ray collects its fine spans chunk by chunk); where they
  // are all homogeneous they are the fine spans too.
  if (!collect_coarse_spans(scene.volumes(), stretch, settings, scratch.march, stack_medium)) return RGB(1.0f);
  if (medium.policy == SecondarySegments::kAuto && collected_spans_homogeneous(scratch.march))
    return march_transmittance_collected(scene.volumes(), stretch, medium.jitter, settings, scratch.march);
  return track_transmittance_chunked(scene.volumes(), stretch, settings, stack_medium, scratch.march, rng,
                                     medium.residual);
}

// Sorts the deferred hits of a shadow ray by t. One crossing can come back twice: the same
// primitive split across BVH leaves, or a ray through the edge two triangles share. Two hits on one
// surface at the same t facing the same way are one crossing; facing opposite ways (grazing a
// silhouette) they stay two, in and out.
void sort_unique_crossings(std::vector<SurfaceHit>& hits, Vec3 d) {
  std::sort(hits.begin(), hits.end(), [](const SurfaceHit& a, const SurfaceHit& b) {
    return a.t != b.t ? a.t < b.t : a.geom_id < b.geom_id;
  });
  hits.erase(std::unique(hits.begin(), hits.end(),
                         [&](const SurfaceHit& a, const SurfaceHit& b) {
                           return a.geom_id == b.geom_id && std::abs(b.t - a.t) <= 1e-6f * (1.0f + std::abs(a.t)) &&
                                  (dot(a.ng, d) < 0.0f) == (dot(b.ng, d) < 0.0f);
                         }),
             hits.end());
}

// What partly transparent surfaces let through along a shadow ray (the product of 1 - opacity);
// 0 when an opaque surface blocks it.
float surface_transparency(const Scene& scene, const Ray& shadow, PathScratch& scratch) {
  std::vector<SurfaceHit>& hits = scratch.shadow_hits;
  hits.clear();
  if (scene.surfaces().occluded(shadow, scene.transparent_geometry(), hits)) return 0.0f;
  sort_unique_crossings(hits, shadow.direction);
  float through = 1.0f;
  for (const SurfaceHit& h : hits) through *= 1.0f - scene.opacity(h);
  return through;
}

RGB nested_transmittance(const Scene& scene, const Ray& shadow, bool casts_shadows, const ShadowMedium& medium,
                         float segment_t, PathScratch& scratch, PathCounters& counters, bool* through_interface) {
  Pcg32 rng(medium.tracking_key, 0);
  MediumStack& stack = scratch.work;
  stack.assign(scratch.stack);
  for (const PendingCrossing& p : scratch.pending)
    if (p.t < segment_t) stack.cross(p.entry);
  std::vector<SurfaceHit>& hits = scratch.shadow_hits;
  hits.clear();
  if (casts_shadows) {
    ++counters.rays;
    if (scene.surfaces().occluded(shadow, scene.shadow_deferred(medium.priority_shadows), hits)) return RGB(0.0f);
  }
  sort_unique_crossings(hits, shadow.direction);
  RGB tr(1.0f);
  Ray stretch = shadow;
  for (size_t i = 0; i <= hits.size(); ++i) {
    stretch.tmax = i < hits.size() ? hits[i].t : shadow.tmax;
    if (stretch.tmax > stretch.tmin)
      tr *= stretch_transmittance(scene, stretch, medium, stack.current().medium, scratch, rng);
    if (tr.is_black()) return RGB(0.0f);
    if (i < hits.size() && scene.is_transparent(hits[i].geom_id)) {
      tr *= 1.0f - scene.opacity(hits[i]);
      stretch.tmin = hits[i].t;
    } else if (i < hits.size()) {
      // Only a REAL dielectric crossing bends the paths MIS would pair this sample with; a
      // hidden one (a false hit) is crossed straight by BSDF and phase samples too.
      bool real = false;
      if (const auto entry = scene.medium_entry(hits[i].geom_id)) real = stack.cross(*entry).real;
      if (through_interface && real && std::holds_alternative<DielectricBsdf>(scene.material(hits[i]).bsdf))
        *through_interface = true;
      stretch.tmin = hits[i].t;
    }
  }
  return tr;
}

}  // namespace

ShadowMedium shadow_medium(const PathContext& ctx, int vertex, bool secondary, sample_dim::Bounce key_dimension) {
  ShadowMedium m(march_jitter(ctx.scene, ctx.sampler, vertex));
  m.priority_shadows = ctx.settings.priority_shadows;
  if (secondary && ctx.settings.secondary != SecondarySegments::kMarch) {
    m.policy = ctx.settings.secondary;
    m.tracking_key = ctx.sampler.stream_key(sample_dim::bounce(vertex, key_dimension));
    m.residual = ctx.settings.residual_ratio_tracking;
  }
  return m;
}

RGB light_transmittance(const Scene& scene, Vec3 origin, Vec3 sampled_from, const LightSample& ls,
                        bool casts_shadows, ShadowMedium medium, PathScratch& scratch, PathCounters& counters,
                        float segment_t, bool* through_interface) {
  if (through_interface) *through_interface = false;
  Ray shadow{origin, ls.wi, 0.0f, kInfinity};
  if (std::isfinite(ls.distance)) {
    shadow.direction = sampled_from + ls.wi * ls.distance - origin;
    shadow.tmax = 1.0f - kShadowEpsilon;
  }
  if (scene.has_priority_objects())
    return nested_transmittance(scene, shadow, casts_shadows, medium, segment_t, scratch, counters, through_interface);
  float through = 1.0f;
  if (casts_shadows) {
    ++counters.rays;
    through = scene.has_transparent_surfaces() ? surface_transparency(scene, shadow, scratch)
                                               : (scene.surfaces().occluded(shadow) ? 0.0f : 1.0f);
    if (!(through > 0.0f)) return RGB(0.0f);
  }
  if (scene.volumes().empty()) return RGB(through);
  Pcg32 rng(medium.tracking_key, 0);
  return stretch_transmittance(scene, shadow, medium, -1, scratch, rng) * through;
}

}  // namespace caligo
