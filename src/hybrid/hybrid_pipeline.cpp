#include "hybrid/hybrid_pipeline.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <variant>

#include "core/enum_names.h"

#include "core/parallel.h"
#include "geometry/mesh_generate.h"
#include "geometry/shapes.h"
#include "realtime/frame_light.h"
#include "realtime/scene_buffers.h"
#include "realtime/shadow_map.h"
#include "scene/scene.h"
#include "volumes/volume_scene.h"

namespace caligo {

struct HybridScatterer::CachedVolumes {
  bool valid = false;
  Vec3 light;
  float extrusion = 0.0f;
  std::vector<ShadowVolume> volumes;
  // A textured spot's blurred gobo, built once per gobo image rather than every frame.
  std::shared_ptr<const GoboImage> gobo_source;
  GoboMips gobo_mips;  // of gobo_source, built once
};

namespace {

constexpr int kSphereSubdivisions = 4;

// The unit icosphere grown so that every face plane lies at distance >= 1 from the centre:
// it then contains the unit sphere and every inscribed tessellation of it (the raster's UV
// sphere), so its shadow volume contains the shadow the shadow map holds.
TriangleMesh circumscribed_sphere(const Sphere& sphere) {
  TriangleMesh m = icosphere(kSphereSubdivisions);
  float min_plane = 1.0f;
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const Vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
               c = m.positions[m.indices[3 * t + 2]];
    const Vec3 n = normalize(cross(b - a, c - a));
    min_plane = std::min(min_plane, std::abs(dot(n, a)));
  }
  const float grow = 1.0f / min_plane * 1.0005f;  // and a little for rounding
  for (Vec3& p : m.positions) p = sphere.object_to_world.point(p * grow);
  m.normals.clear();
  return m;
}

struct ConvexCheck {
  bool operator()(const SphereVolumeShape&) const { return true; }
  bool operator()(const BoxVolumeShape&) const { return true; }
  bool operator()(const MeshVolumeShape&) const { return false; }
  bool operator()(const UnboundedVolumeShape&) const { return false; }
};

bool inside(const VolumeShape& shape, Vec3 p) {
  // A short ray from p: p is inside a convex hull when the hull interval starts at p.
  const Ray ray{p, Vec3(0, 1, 0), 0.0f, kInfinity};
  const auto hull = volume_hull_interval(shape, ray);
  return hull && hull->t0 <= 0.0f && hull->t1 > 0.0f;
}

// The opaque depth cut at the medium's exit, so every pass integrates the lit medium only, and
// the radius around the light of a ball holding every visible point and the eye.
struct ClippedDepth {
  Plane depth;
  float light_reach = 0.0f;  // max(|eye - light|, |p - light| over visible points p); inf: sky
};

ClippedDepth clip_to_medium(const Plane& depth, const View& view, const VolumeShape& shape, Vec3 light) {
  ClippedDepth out{Plane(depth.width, depth.height), distance(view.eye, light)};
  std::vector<float> row_reach(size_t(depth.height), 0.0f);
  parallel_for(depth.height, [&](int y) {
    float reach = 0.0f;
    for (int x = 0; x < depth.width; ++x) {
      Ray ray = view.ray({float(x) + 0.5f, float(y) + 0.5f});
      ray.tmin = 0.0f;
      ray.tmax = kInfinity;
      const auto hull = volume_hull_interval(shape, ray);
      const float per_t = view.depth_per_t(ray.direction);
      const float exit_depth = hull ? hull->t1 * per_t : 0.0f;
      const float d = std::min(depth.at(x, y), exit_depth);
      out.depth.at(x, y) = d;
      const float t = per_t > 0.0f && d < kSkyDepth ? d / per_t : kInfinity;
      reach = std::max(reach, distance(ray.at(t), light));
    }
    row_reach[size_t(y)] = reach;
  });
  for (float r : row_reach) out.light_reach = std::max(out.light_reach, r);
  if (!std::isfinite(out.light_reach)) out.light_reach = kInfinity;
  return out;
}

// The pass's view of the one homogeneous medium (density folded in).
ScatteringMedium scattering_medium(const VolumePrimitive& medium) {
  const float density = medium.shader.density;
  return {medium.shader.sigma_s * density, (medium.shader.sigma_a + medium.shader.sigma_s) * density,
          medium.shader.phase};
}

// Why the scene's media are outside the model for this eye and light ("" when inside): one
// homogeneous, convex medium containing both, isotropic unless `any_phase` (Hoffman–Preetham).
std::string medium_problem(const VolumeScene& volumes, Vec3 eye, Vec3 light, bool any_phase = false) {
  if (volumes.primitives().size() != 1)
    return std::to_string(volumes.primitives().size()) + " volume primitives (the model takes one)";
  const VolumePrimitive& medium = volumes.primitive(0);
  if (!is_homogeneous(medium.shader)) return "the medium is not homogeneous";
  if (!std::visit(ConvexCheck{}, medium.shape)) return "a mesh-bounded medium";
  if (!any_phase && !scattering_medium(medium).isotropic())
    return "an anisotropic phase function (the airlight is isotropic)";
  if (!inside(medium.shape, eye) || !inside(medium.shape, light)) return "the eye or the light is outside the medium";
  return "";
}


}  // namespace

namespace {
constexpr std::array<EnumName<VolumetricMethod>, 5> kVolumetricMethodNames{{{VolumetricMethod::kMarch, "march"},
                                                                           {VolumetricMethod::kNone, "none"},
                                                                           {VolumetricMethod::kBrute, "brute"},
                                                                           {VolumetricMethod::kHybrid, "hybrid"},
                                                                           {VolumetricMethod::kTextured, "textured"}}};
}  // namespace

std::optional<VolumetricMethod> parse_volumetric_method(std::string_view name) {
  return enum_from_name(kVolumetricMethodNames, name);
}

const char* volumetric_method_name(VolumetricMethod method) {
  return enum_name(kVolumetricMethodNames, method).data();
}

HybridScatterer::HybridScatterer(const Scene& scene, VolumetricMethod method, HybridSettings settings,
                                 TexturedSpotSettings spot_settings)
    : method_(method), settings_(settings), spot_settings_(spot_settings) {
  const EmbreeScene& surfaces = scene.surfaces();
  scene_bounds_ = surfaces.bounds();
  if (method_ != VolumetricMethod::kHybrid && method_ != VolumetricMethod::kTextured) return;
  for (uint32_t g = 0; g < uint32_t(surfaces.geometry_count()); ++g) {
    SurfaceHit hit;
    hit.geom_id = g;
    // Null surfaces cast no shadow (the raster scene leaves them out of the shadow maps too).
    if (std::holds_alternative<NullBsdf>(scene.material(hit).bsdf)) continue;
    // A shape's proxy (ShapeDesc::proxy, closed) stands in for its shadow volumes.
    if (const TriangleMesh* proxy = scene.shadow_proxy(g)) {
      occluders_.push_back(MeshEdges(*proxy));
      continue;
    }
    const TriangleMesh mesh = surfaces.is_sphere(g) ? circumscribed_sphere(surfaces.sphere(g)) : surfaces.mesh(g);
    MeshEdges edges(mesh);
    if (!edges.closed()) {
      if (open_occluder_.empty()) open_occluder_ = "geometry " + std::to_string(g) + ": " + edges.problem();
      // Its bounding box stands in (a closed proxy whose shadow holds the mesh's): the
      // scattering pass then marches every ray whose end lies in a shadow volume up to its
      // surface, since inside a proxy's volume is not necessarily in shadow.
      occluders_.push_back(MeshEdges(bounding_box_proxy(mesh)));
      settings_.conservative_tails = true;
      continue;
    }
    occluders_.push_back(std::move(edges));
  }
  if (!open_occluder_.empty())
    std::fprintf(stderr,
                 "caligo realtime: warning: --method %s: occluder %s; its shadow volume is its bounding box's, "
                 "and rays ending in a shadow volume are marched to their surface%s\n",
                 volumetric_method_name(method_), open_occluder_.c_str(),
                 method_ == VolumetricMethod::kTextured ? "; spot lights read the shadow map at every step" : "");
}

HybridScatterer::~HybridScatterer() = default;

TriangleMesh bounding_box_proxy(const TriangleMesh& mesh) {
  Bounds3 b;
  for (Vec3 p : mesh.positions) b.extend(p);
  if (b.empty()) return {};
  // Grown a little so that a flat mesh (a card, a ground plane) still bounds a volume.
  const Vec3 margin = b.diagonal() * 1e-3f + Vec3(1e-4f);
  return box_mesh(b.lo - margin, b.hi + margin);
}

VolumetricMethod HybridScatterer::used(size_t index) const {
  return index < used_.size() ? used_[index] : VolumetricMethod::kMarch;
}

void HybridScatterer::note(size_t index, const std::string& why) {
  if (noted_[index]) return;
  noted_[index] = true;
  std::fprintf(stderr, "caligo realtime: note: light %zu uses the march, not --method %s: %s\n", index,
               volumetric_method_name(method_), why.c_str());
}

ShadowVolumeBuffers HybridScatterer::shadow_volume_buffers(size_t index, Vec3 light, float light_reach,
                                                           const View& low_view, const Plane& depth) {
  CachedVolumes& cache = cache_[index];
  // Extrusion: every visible point and the eye lie within light_reach of the light, and so does
  // every view ray's stretch up to its surface (a ball is convex). Extruded past that reach,
  // the volumes hold every shadowed visible point and their far caps lie outside the ball, where
  // no ray counts them: they are left out, which is exact. Shorter volumes also make shorter
  // slivers on screen than extruding past the whole scene. Rebuilt when the light moves or the
  // reach outgrows the cached length (or shrinks to under half of it).
  const float needed = std::isfinite(light_reach) ? 1.02f * light_reach + 0.05f
                                                          : extrusion_for(scene_bounds_, light);
  if (!cache.valid || !(cache.light == light) || cache.extrusion < needed ||
      cache.extrusion > 2.0f * needed) {
    cache.volumes.clear();
    for (const MeshEdges& o : occluders_) cache.volumes.push_back(build_shadow_volume(o, light, needed));
    cache.light = light;
    cache.extrusion = needed;
    cache.valid = true;
  }
  ShadowVolumeOptions options;
  options.far_caps = std::any_of(cache.volumes.begin(), cache.volumes.end(), [&](const ShadowVolume& v) {
    return !(light_reach < 0.999f * v.min_far_distance);
  });
  return rasterize_shadow_volumes(cache.volumes, low_view, depth, options);
}

bool HybridScatterer::scatter(size_t index, const FrameLight& frame_light, const VolumeScene& volumes,
                              const View& low_view, const Plane& low_depth, ColorPlanes& accum) {
  if (used_.size() <= index) {
    used_.resize(index + 1, VolumetricMethod::kMarch);
    noted_.resize(index + 1, false);
    cache_.resize(index + 1);
  }
  used_[index] = VolumetricMethod::kMarch;
  if (method_ == VolumetricMethod::kMarch) return false;
  const PointLight* point = std::get_if<PointLight>(&frame_light.light);
  const SpotLight* spot = std::get_if<SpotLight>(&frame_light.light);
  if (method_ == VolumetricMethod::kTextured && spot) return scatter_spot(index, *spot, frame_light, volumes, low_view, low_depth, accum);
  if (!point) return note(index, "not a point light"), false;
  if (point->ies.profile || std::isfinite(point->range))
    return note(index, "an IES profile or a finite range is outside the airlight model"), false;
  if (const std::string why = medium_problem(volumes, low_view.eye, point->position); !why.empty())
    return note(index, why), false;
  const VolumePrimitive& medium = volumes.primitive(0);

  VolumetricMethod method = method_ == VolumetricMethod::kTextured ? VolumetricMethod::kHybrid : method_;
  if (!frame_light.shadow) method = VolumetricMethod::kNone;  // casts no shadow: the airlight is exact

  const ScatteringMedium coefficients = scattering_medium(medium);
  const ClippedDepth clipped = clip_to_medium(low_depth, low_view, medium.shape, point->position);
  const Plane& depth = clipped.depth;

  const ShadowVolumeBuffers* buffers = nullptr;
  ShadowVolumeBuffers sv;
  if (method == VolumetricMethod::kHybrid) {
    sv = shadow_volume_buffers(index, point->position, clipped.light_reach, low_view, depth);
    buffers = &sv;
  }

  const RGB weight = point->intensity * frame_light.options.volumetric_intensity;
  if (!scatter_channels(method, coefficients, point->position, weight, frame_light, low_view, depth, buffers,
                        accum))
    return false;
  used_[index] = method;
  return true;
}

// The airlight passes for one point light, once for a grey medium, once per channel otherwise.
bool HybridScatterer::scatter_channels(VolumetricMethod method, const ScatteringMedium& medium, Vec3 position,
                                       RGB weight,
                                       const FrameLight& frame_light, const View& low_view, const Plane& depth,
                                       const ShadowVolumeBuffers* buffers, ColorPlanes& accum) const {
  const AirlightTable& table = AirlightTable::shared();
  const bool grey = medium.grey();
  const int passes = grey ? 1 : 3;
  for (int c = 0; c < passes; ++c) {
    const AirlightMedium m{medium.sigma_s[c], medium.sigma_t[c]};
    const HybridLight light{position, 1.0f, RGB(1.0f)};
    ColorPlanes result;
    switch (method) {
      case VolumetricMethod::kNone:
        result = scatter_unshadowed(low_view, depth, table, m, light, settings_);
        break;
      case VolumetricMethod::kBrute:
        result = scatter_brute(low_view, depth, *frame_light.shadow, table, m, light, settings_).radiance;
        break;
      case VolumetricMethod::kHybrid:
        result = scatter_hybrid(low_view, depth, *buffers, *frame_light.shadow, table, m, light, settings_).radiance;
        break;
      case VolumetricMethod::kMarch:
      case VolumetricMethod::kTextured:
        return false;  // handled by scatter()
    }
    RGB w = weight;
    if (!grey) w = RGB(c == 0 ? weight.r : 0.0f, c == 1 ? weight.g : 0.0f, c == 2 ? weight.b : 0.0f);
    accum.add(result, w);
  }
  return true;
}

bool HybridScatterer::scatter_spot(size_t index, const SpotLight& spot, const FrameLight& frame_light,
                                   const VolumeScene& volumes, const View& low_view, const Plane& low_depth,
                                   ColorPlanes& accum) {
  // Hoffman–Preetham takes any phase; the airlight (forced, or kAuto's pick) an isotropic one.
  const bool any_phase = spot_settings_.model != SpotScatterModel::kAirlight;
  if (const std::string why = medium_problem(volumes, low_view.eye, spot.position, any_phase); !why.empty())
    return note(index, why), false;
  const VolumePrimitive& primitive = volumes.primitive(0);
  const ScatteringMedium medium = scattering_medium(primitive);
  const ClippedDepth clipped = clip_to_medium(low_depth, low_view, primitive.shape, spot.position);
  // The spot's shadow volumes cut each frustum stretch into segments sampled at their own
  // rates; with an open occluder, every step reads the shadow map.
  const ShadowVolumeBuffers* buffers = nullptr;
  ShadowVolumeBuffers sv;
  if (frame_light.shadow && open_occluder_.empty()) {
    sv = shadow_volume_buffers(index, spot.position, clipped.light_reach, low_view, clipped.depth);
    buffers = &sv;
  }
  // The pass carries the spot's colour (intensity, cone, gobo) and the medium's per channel.
  const GoboMips* mips = nullptr;
  if (spot.gobo.image) {
    CachedVolumes& cache = cache_[index];
    if (cache.gobo_source != spot.gobo.image) {
      cache.gobo_mips = gobo_mips(spot.gobo.image);
      cache.gobo_source = spot.gobo.image;
    }
    mips = &cache.gobo_mips;
  }
  const ScatterResult r =
      scatter_textured_spot(low_view, clipped.depth, frame_light.shadow, medium, spot, spot_settings_, buffers, mips);
  accum.add(r.radiance, RGB(frame_light.options.volumetric_intensity));
  used_[index] = VolumetricMethod::kTextured;
  return true;
}

}  // namespace caligo
