#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/message_text.h"
#include "core/overloaded.h"
#include "geometry/mesh_closure.h"
#include "geometry/mesh_generate.h"
#include "geometry/shapes.h"
#include "scene/mesh_loader.h"

namespace caligo {
namespace {

bool emits(const Material& m) { return !m.emission.is_black(); }

// A sphere transform that is a similarity (uniform scale, rotation, translation) keeps it a
// sphere, which the sphere light's cone sampling requires.
std::optional<SphereLight> as_sphere_light(const Sphere& s, const Material& m) {
  const Transform& t = s.object_to_world;
  const float rx = length(t.vector({1, 0, 0})), ry = length(t.vector({0, 1, 0})),
              rz = length(t.vector({0, 0, 1}));
  const float tolerance = 1e-4f * rx;
  if (std::abs(rx - ry) > tolerance || std::abs(rx - rz) > tolerance ||
      std::abs(dot(t.vector({1, 0, 0}), t.vector({0, 1, 0}))) > tolerance * rx)
    return std::nullopt;
  return SphereLight{t.point({}), rx, m.emission, m.two_sided_emission};
}

// Built piecewise: GCC 12 warns falsely (-Wrestrict) about `"literal" + std::string`.
std::string light_material_name(const char* kind, int index) {
  std::string name = "<";
  name += kind;
  name += " light ";
  name += std::to_string(index);
  name += '>';
  return name;
}

struct ShapeMesh {
  const ShapeDesc& shape;
  TriangleMesh operator()(const BoxShape& b) const { return box_mesh(b.min, b.max); }
  TriangleMesh operator()(const RectangleShape& r) const {
    return rectangle_mesh(r.corner, r.edge1, r.edge2);
  }
  TriangleMesh operator()(const MeshFileShape& m) const {
    return load_mesh(m.path, shape.where,
                     m.skip_degenerate ? DegenerateTriangles::kRemove : DegenerateTriangles::kReject);
  }
  TriangleMesh operator()(const InlineMeshShape& m) const { return *m.mesh; }
  TriangleMesh operator()(const GeneratedMeshShape& g) const {
    switch (g.kind) {
      case GeneratedMeshShape::Kind::kSphere:
        return icosphere(icosphere_subdivisions_for(g.triangles));
      case GeneratedMeshShape::Kind::kTorusKnot:
        return torus_knot(torus_knot_for(g.triangles));
    }
    throw std::logic_error("unknown generated mesh");
  }
  TriangleMesh operator()(const SphereShape&) const { throw std::logic_error("spheres are not meshed"); }
};

}  // namespace

std::unique_ptr<Scene> Scene::build(const SceneDesc& desc) {
  std::unique_ptr<Scene> scene(new Scene());
  scene->desc_ = desc;
  scene->materials_ = desc.materials;
  scene->lights_ = desc.lights;
  for (const ShapeDesc& shape : desc.shapes) scene->add_shape(shape);
  for (size_t i = 0; i < desc.lights.size(); ++i) scene->add_light_geometry(int(i));
  scene->surfaces_.commit();
  // The media materials enclose, as unbounded primitives beside the volume primitives.
  std::vector<VolumePrimitive> media;
  scene->interior_slot_.assign(desc.media.size(), -1);
  for (const Material& m : desc.materials) {
    if (m.priority == kPriorityOff || m.interior < 0 || scene->interior_slot_[size_t(m.interior)] >= 0) continue;
    scene->interior_slot_[size_t(m.interior)] = int(media.size());
    media.push_back({UnboundedVolumeShape{}, desc.media[size_t(m.interior)].shader, m.interior});
  }
  scene->volumes_ = VolumeScene(desc.volumes, std::move(media));
  // The emission connections march their line through the volume primitives alone: with
  // priority surfaces (media inside surfaces, whose stack a line would have to track) emission
  // is left to bounce rays.
  if (!scene->has_priority_objects_) {
    VolumeContext context;
    scene->emission_sampler_ = EmissionSampler::build(scene->volumes_, context);
  }
  scene->finish_lights();
  if (scene->has_priority_objects_) scene->camera_stack_ = scene->stack_at(desc.camera.position);
  return scene;
}

std::optional<MediumEntry> Scene::medium_entry(uint32_t geom_id) const {
  const Material& m = materials_[size_t(geometry_[geom_id].material)];
  if (m.priority == kPriorityOff) return std::nullopt;
  return MediumEntry{geom_id, m.priority, {m.interior >= 0 ? interior_slot_[size_t(m.interior)] : -1, m.ior}};
}

MediumStack Scene::stack_at(Vec3 p) const {
  MediumStack stack;
  if (!has_priority_objects_) return stack;
  std::vector<SurfaceHit> hits;
  surfaces_.all_hits(Ray{p, Vec3(0, 1, 0), 0.0f, kInfinity}, hits);
  // Each object's first crossing (hits are sorted by t); leaving through it means inside.
  struct Inside {
    float t;
    MediumEntry entry;
  };
  std::vector<Inside> inside;
  std::vector<uint8_t> seen(geometry_.size(), 0);
  for (const SurfaceHit& h : hits) {
    if (seen[h.geom_id]) continue;
    seen[h.geom_id] = 1;
    const auto entry = medium_entry(h.geom_id);
    if (entry && h.ng.y > 0.0f) inside.push_back({h.t, *entry});
  }
  // Outermost (farthest first crossing) entered first, as a ray from outside would.
  std::sort(inside.begin(), inside.end(), [](const Inside& a, const Inside& b) { return a.t > b.t; });
  for (const Inside& i : inside) stack.cross(i.entry);
  return stack;
}

int Scene::add_geometry(uint32_t geom_id, GeometryInfo info) {
  if (geom_id != geometry_.size()) throw std::logic_error("Embree geometry ids must be dense");
  geometry_.push_back(info);
  const Material& m = materials_[size_t(info.material)];
  const bool null = std::holds_alternative<NullBsdf>(m.bsdf);
  // Priority surfaces are seen by every shadow query (plain occluded() treats them as
  // blockers); the path tracer's shadow rays defer the ones listed here to the medium stack.
  const bool priority = m.priority != kPriorityOff;
  has_priority_objects_ = has_priority_objects_ || priority;
  surfaces_.set_casts_shadows(geom_id, priority || !null);
  const bool transparent = partly_transparent(m);
  has_transparent_surfaces_ = has_transparent_surfaces_ || transparent;
  transparent_.push_back(transparent ? 1 : 0);
  shadow_deferred_[0].push_back((priority && null) || transparent ? 1 : 0);
  shadow_deferred_[1].push_back(priority || transparent ? 1 : 0);
  return int(geom_id);
}

void Scene::add_shape(const ShapeDesc& shape) {
  const size_t first = geometry_.size();
  add_shape_geometry(shape);
  int proxy = -1;
  if (shape.proxy) {
    const ShapeGeometry& g = *shape.proxy;
    TriangleMesh mesh;
    if (const auto* s = std::get_if<SphereShape>(&g)) {
      // Four subdivisions (5,120 triangles) of the unit sphere, circumscribing the true one a little.
      mesh = icosphere(4);
      for (Vec3& p : mesh.positions) p = s->center + p * (s->radius * 1.002f);
    } else {
      ShapeDesc proxy_shape = shape;
      proxy_shape.geometry = g;
      mesh = std::visit(ShapeMesh{proxy_shape}, g);
    }
    transform_mesh(mesh, shape.transform);
    const MeshClosure c = check_closure(mesh);
    if (c.boundary_edges + c.non_manifold_edges + c.misoriented_edges > 0)
      throw InputError(shape.where, "the shadow proxy is not a closed, consistently wound surface (" +
                                        std::to_string(c.boundary_edges) + " boundary, " +
                                        std::to_string(c.non_manifold_edges) + " non-manifold, " +
                                        std::to_string(c.misoriented_edges) + " misoriented edges)");
    proxy = int(proxies_.size());
    proxies_.push_back(std::move(mesh));
  }
  for (size_t g = first; g < geometry_.size(); ++g) {
    geometry_[g].holdout = shape.holdout;
    geometry_[g].proxy = proxy;
  }
}

void Scene::add_shape_geometry(const ShapeDesc& shape) {
  const Material& material = materials_[size_t(shape.material)];
  if (partly_transparent(material) && shape.holdout)
    throw InputError(shape.where, "a holdout cannot be partly transparent (material " +
                                      quote_for_message(material.name) + " has an \"opacity\")");
  if (material.opacity_map && std::holds_alternative<SphereShape>(shape.geometry))
    throw InputError(shape.where, "material " + quote_for_message(material.name) +
                                      " has an opacity image, but a sphere has no texture coordinates (use a mesh "
                                      "or a rectangle)");
  if (const auto* s = std::get_if<SphereShape>(&shape.geometry)) {
    const Sphere sphere = Sphere::make(s->center, s->radius, shape.transform);
    GeometryInfo info{shape.material};
    if (emits(material)) {
      const auto light = as_sphere_light(sphere, material);
      if (!light)
        throw InputError(shape.where,
                         "an emissive sphere must be scaled uniformly (it becomes a sphere light)");
      info.light = int(lights_.size());
      lights_.push_back(*light);
    }
    add_geometry(surfaces_.add_sphere(sphere), info);
    return;
  }
  TriangleMesh mesh = std::visit(ShapeMesh{shape}, shape.geometry);
  transform_mesh(mesh, shape.transform);
  if (emits(material)) {
    add_emitting_mesh(std::move(mesh), shape.material, shape.where);
    return;
  }
  if (material.opacity_map && mesh.uvs.empty())
    throw InputError(shape.where, "material " + quote_for_message(material.name) +
                                      " has an opacity image, but this mesh has no texture coordinates");
  try {
    add_geometry(surfaces_.add_mesh(std::move(mesh)), {shape.material});
  } catch (const std::invalid_argument& e) {
    throw InputError(shape.where, e.what());
  }
}

void Scene::add_emitting_mesh(TriangleMesh mesh, int material, const SourceLocation& where) {
  const Material& m = materials_[size_t(material)];
  const int first = int(lights_.size());
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const uint32_t* tri = &mesh.indices[3 * t];
    lights_.push_back(TriangleLight{mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]],
                                    m.emission, m.two_sided_emission});
  }
  try {
    add_geometry(surfaces_.add_mesh(std::move(mesh)), {material, first, true});
  } catch (const std::invalid_argument& e) {
    throw InputError(where, e.what());
  }
}

// Area lights are visible (lights/types/*.cpp's surface()): each gets its geometry with a
// black, emitting material. Triangle lights come with their shape's mesh instead.
void Scene::add_light_geometry(int index) {
  const Light& light = lights_[size_t(index)];
  auto visible = visible_geometry(light);
  if (!visible) return;
  materials_.push_back({light_material_name(light_type_name(light), index), BlackBsdf{}, visible->radiance,
                        visible->two_sided});
  const GeometryInfo info{int(materials_.size()) - 1, index};
  std::visit(Overloaded{[&](const VisibleSphere& s) {
                          add_geometry(surfaces_.add_sphere(Sphere::make(s.centre, s.radius, {})), info);
                        },
                        [&](VisibleTriangles& t) {
                          TriangleMesh mesh;
                          mesh.positions = std::move(t.positions);
                          mesh.indices = std::move(t.indices);
                          add_geometry(surfaces_.add_mesh(mesh), info);
                        }},
             visible->shape);
}

void Scene::finish_lights() {
  const Bounds3 b = surfaces_.bounds();
  const float radius = b.empty() ? 1.0f : std::max(1e-3f, 0.5f * length(b.diagonal()));
  for (size_t i = 0; i < lights_.size(); ++i) {
    Light& light = lights_[i];
    set_scene_radius(light, radius);
    if (is_infinite(light)) infinite_lights_.push_back(int(i));
  }
  for (const auto& [kind, name] : kLightSamplerNames) light_samplers_[size_t(kind)] = LightSampler(kind, lights_);
}

SurfaceInteraction Scene::interaction(const Ray& ray, const SurfaceHit& hit) const {
  const GeometryInfo& info = geometry_[hit.geom_id];
  SurfaceInteraction si;
  si.p = ray.at(hit.t);
  si.ng = hit.ng;
  si.ns = hit.ng;
  si.material = &materials_[size_t(info.material)];
  if (info.light >= 0) si.light = info.light + (info.light_per_primitive ? int(hit.prim_id) : 0);
  if (!surfaces_.is_sphere(hit.geom_id)) {
    const TriangleMesh& mesh = surfaces_.mesh(hit.geom_id);
    if (!mesh.normals.empty()) {
      const uint32_t* tri = &mesh.indices[3 * size_t(hit.prim_id)];
      const float b1 = hit.uv.x, b2 = hit.uv.y, b0 = 1.0f - b1 - b2;
      const Vec3 n = mesh.normals[tri[0]] * b0 + mesh.normals[tri[1]] * b1 + mesh.normals[tri[2]] * b2;
      if (length_squared(n) > 0.0f) si.ns = face_forward(normalize(n), si.ng);
    }
  }
  return si;
}

float Scene::opacity(const SurfaceHit& hit) const {
  const Material& m = material(hit);
  if (!m.opacity_map) return m.opacity;
  // Meshes only (add_shape_geometry refuses maps elsewhere); uvs interpolated by the barycentrics.
  const TriangleMesh& mesh = surfaces_.mesh(hit.geom_id);
  const uint32_t* tri = &mesh.indices[3 * size_t(hit.prim_id)];
  const float b1 = hit.uv.x, b2 = hit.uv.y, b0 = 1.0f - b1 - b2;
  const Vec2 a = mesh.uvs[tri[0]], b = mesh.uvs[tri[1]], c = mesh.uvs[tri[2]];
  const Vec2 uv{a.x * b0 + b.x * b1 + c.x * b2, a.y * b0 + b.y * b1 + c.y * b2};
  return m.opacity * m.opacity_map->lookup(uv);
}

std::optional<SurfaceHit> nearest_non_null_hit(const Scene& scene, Ray ray, int max_crossings, uint64_t* queries,
                                               std::vector<SurfaceHit>* layers) {
  if (layers) layers->clear();
  for (int crossings = 0; crossings <= max_crossings; ++crossings) {
    if (queries) ++*queries;
    const auto hit = scene.surfaces().intersect(ray);
    if (!hit) return std::nullopt;
    if (layers && scene.is_transparent(hit->geom_id))
      layers->push_back(*hit);
    else if (!std::holds_alternative<NullBsdf>(scene.material(*hit).bsdf))
      return hit;
    ray.tmin = hit->t + std::max(1e-4f, hit->t * 1e-5f);
  }
  return std::nullopt;
}

}  // namespace caligo
