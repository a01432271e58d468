// The immutable Scene every pipeline reads: built once from a SceneDesc, then shared
// read-only by all render threads. Owns the Embree scene, the materials, the lights and
// the light-selection distribution, and maps each surface hit back to its material and,
// for emitters, to its light.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "core/sampling.h"
#include "geometry/embree_scene.h"
#include "lights/light.h"
#include "lights/light_sampler.h"
#include "volumes/emission_sampler.h"
#include "materials/material.h"
#include "media/medium_stack.h"
#include "scene/camera.h"
#include "scene/scene_desc.h"
#include "volumes/volume_scene.h"

namespace caligo {

// What the integrator needs to know about a surface hit.
struct SurfaceInteraction {
  Vec3 p;   // world position
  Vec3 ng;  // unit geometric normal (outward for closed shapes)
  Vec3 ns;  // unit shading normal, on the same side as ng
  const Material* material = nullptr;
  int light = -1;  // index into Scene::lights() when the surface emits
};

class Scene {
 public:
  // Throws InputError (located in the scene file) for meshes that fail to load or validate.
  static std::unique_ptr<Scene> build(const SceneDesc& desc);

  const SceneDesc& desc() const { return desc_; }
  const EmbreeScene& surfaces() const { return surfaces_; }
  const VolumeScene& volumes() const { return volumes_; }
  // Emissive grids as lights (volumes/emission_sampler.h); empty when none can be sampled.
  const EmissionSampler& emission_sampler() const { return emission_sampler_; }
  const std::vector<Material>& materials() const { return materials_; }
  const std::vector<Light>& lights() const { return lights_; }
  const std::vector<int>& infinite_lights() const { return infinite_lights_; }
  // The light-sampler seam (lights/light_sampler.h): every strategy, built once with the scene
  // (the tree costs a few microseconds per light).
  const LightSampler& light_sampler(LightSamplerKind kind) const { return light_samplers_[size_t(kind)]; }

  // False for a light whose scene entry says "shadow": false (Arnold's cast_shadows):
  // surfaces do not block it, media still attenuate it. Lights made from emissive shapes
  // always cast shadows.
  bool casts_shadows(int light) const {
    return size_t(light) >= desc_.lights.size() || desc_.options(size_t(light)).shadow;
  }

  SurfaceInteraction interaction(const Ray& ray, const SurfaceHit& hit) const;

  // Nested dielectrics (media/medium_stack.h). The stack entry of a hit surface whose material
  // has a priority (its inside medium is a slot of volumes()' media), or nullopt for priority Off.
  std::optional<MediumEntry> medium_entry(uint32_t geom_id) const;
  // True when some surface has a priority: paths then carry a medium stack.
  bool has_priority_objects() const { return has_priority_objects_; }
  // Per geometry: 1 when shadow rays defer its hits to the stack instead of being blocked:
  // priority null boundaries always, priority dielectrics too when `priority_shadows`
  // (PathSettings::priority_shadows).
  const std::vector<uint8_t>& shadow_deferred(bool priority_shadows) const {
    return shadow_deferred_[priority_shadows ? 1 : 0];
  }
  // The media around the camera at build time: one probe ray from the camera straight up
  // (+Y) through every surface; an object whose first crossing along it leaves it (the probe
  // runs along that face's geometric normal) contains the camera. Works for open surfaces such as a
  // water plane whose normal points out of the water.
  const MediumStack& camera_stack() const { return camera_stack_; }
  // The same probe from any point.
  MediumStack stack_at(Vec3 p) const;
  // Partly transparent surfaces (materials/opacity_map.h): some material has an opacity below 1 or
  // a map. Per geometry, 1 for those (a mask for EmbreeScene::occluded's deferred hits; shadow_deferred
  // lists them too).
  bool has_transparent_surfaces() const { return has_transparent_surfaces_; }
  const std::vector<uint8_t>& transparent_geometry() const { return transparent_; }
  bool is_transparent(uint32_t geom_id) const { return transparent_[geom_id] != 0; }
  // The opacity of the surface at a hit: the material's number times its map at the hit's texture
  // coordinates; 1 for opaque surfaces.
  float opacity(const SurfaceHit& hit) const;
  // The shadow-volume stand-in of a geometry (ShapeDesc::proxy, closed, world space), or null.
  const TriangleMesh* shadow_proxy(uint32_t geom_id) const {
    const int p = geometry_[geom_id].proxy;
    return p < 0 ? nullptr : &proxies_[size_t(p)];
  }
  // A holdout shape (ShapeDesc::holdout).
  bool is_holdout(uint32_t geom_id) const { return geometry_[geom_id].holdout; }
  // The light whose surface a geometry is (its first light for an emissive mesh), or -1.
  int geometry_light(uint32_t geom_id) const { return geometry_[geom_id].light; }
  const Material& material(const SurfaceHit& hit) const {
    return materials_[size_t(geometry_[hit.geom_id].material)];
  }
  Camera camera(Vec2i resolution) const { return Camera(desc_.camera, resolution); }

 private:
  struct GeometryInfo {
    int material = 0;
    int light = -1;                    // first light of this geometry, or -1
    bool light_per_primitive = false;  // emissive meshes: one TriangleLight per triangle
    bool holdout = false;              // ShapeDesc::holdout
    int proxy = -1;                    // index into proxies_
  };

  Scene() = default;
  void add_shape(const ShapeDesc& shape);
  void add_shape_geometry(const ShapeDesc& shape);
  void add_light_geometry(int light_index);
  void add_emitting_mesh(TriangleMesh mesh, int material, const SourceLocation& where);
  int add_geometry(uint32_t geom_id, GeometryInfo info);
  void finish_lights();

  SceneDesc desc_;
  EmbreeScene surfaces_;
  VolumeScene volumes_;
  EmissionSampler emission_sampler_;
  std::vector<Material> materials_;
  std::vector<GeometryInfo> geometry_;  // indexed by Embree geometry id
  std::vector<Light> lights_;
  std::vector<int> infinite_lights_;
  std::array<LightSampler, kLightSamplerNames.size()> light_samplers_;  // indexed by LightSamplerKind
  std::vector<int> interior_slot_;  // per SceneDesc medium: its slot in volumes_' media, or -1
  std::array<std::vector<uint8_t>, 2> shadow_deferred_;  // without, with priority_shadows
  std::vector<uint8_t> transparent_;                    // per geometry: partly transparent
  std::vector<TriangleMesh> proxies_;                   // ShapeDesc::proxy meshes, world space
  bool has_priority_objects_ = false;
  bool has_transparent_surfaces_ = false;
  MediumStack camera_stack_;
};

// How many null surfaces in a row a ray steps over before giving up (endless chains of them).
inline constexpr int kMaxNullCrossings = 256;

// The nearest surface along the ray that is not a null surface (Off null surfaces, the bounds of
// media seen from outside, are stepped over by a relative epsilon of their distance, so what lies
// in front of the hit stays one segment). `queries` counts the Embree queries when given. Every
// pipeline's camera and bounce rays in scenes without priority surfaces find their hit here.
// With `layers`, partly transparent surfaces are stepped over too and listed there in order (the
// path tracer's march records them); without, they are hits like any other.
std::optional<SurfaceHit> nearest_non_null_hit(const Scene& scene, Ray ray, int max_crossings = kMaxNullCrossings,
                                               uint64_t* queries = nullptr, std::vector<SurfaceHit>* layers = nullptr);

}  // namespace caligo
