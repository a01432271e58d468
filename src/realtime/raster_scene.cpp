// RasterScene: the scene's opaque surfaces as flat world-space triangles.
#include <cmath>

#include "geometry/shapes.h"
#include "realtime/scene_buffers.h"
#include "scene/scene.h"

namespace caligo {
namespace {

int32_t material_index(const Scene& scene, uint32_t geom_id) {
  SurfaceHit hit;
  hit.geom_id = geom_id;
  return int32_t(&scene.material(hit) - scene.materials().data());
}

void add_mesh(RasterScene& out, const TriangleMesh& mesh, int32_t material, int32_t emitter) {
  const bool has_normals = !mesh.normals.empty();
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const uint32_t* tri = &mesh.indices[3 * t];
    const Vec3 p0 = mesh.positions[tri[0]], p1 = mesh.positions[tri[1]], p2 = mesh.positions[tri[2]];
    const Vec3 c = cross(p1 - p0, p2 - p0);
    if (!(length_squared(c) > 0.0f)) continue;
    const Vec3 ng = normalize(c);
    // Shading normals point to the geometric normal's side, as Scene::interaction makes them.
    auto shading = [&](uint32_t v) {
      if (!has_normals || !(length_squared(mesh.normals[v]) > 0.0f)) return ng;
      return face_forward(normalize(mesh.normals[v]), ng);
    };
    out.add_triangle(p0, p1, p2, shading(tri[0]), shading(tri[1]), shading(tri[2]), material, emitter);
  }
}

// A UV sphere through the sphere's transform (ellipsoids stay ellipsoids); triangles wound
// so their geometric normals point outwards like Embree's sphere normals.
void add_sphere(RasterScene& out, const Sphere& sphere, int32_t material, int32_t emitter) {
  constexpr int kSeg = RasterScene::kSphereSegments, kRings = RasterScene::kSphereRings;
  const Transform& t = sphere.object_to_world;
  const Vec3 centre = t.point({0, 0, 0});
  auto unit = [](int ring, int seg) {
    const float theta = kPi * float(ring) / float(kRings), phi = 2.0f * kPi * float(seg % kSeg) / float(kSeg);
    return Vec3{std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
  };
  auto emit = [&](Vec3 u0, Vec3 u1, Vec3 u2) {
    Vec3 p[3] = {t.point(u0), t.point(u1), t.point(u2)};
    Vec3 n[3] = {normalize(t.normal(u0)), normalize(t.normal(u1)), normalize(t.normal(u2))};
    const Vec3 c = cross(p[1] - p[0], p[2] - p[0]);
    if (dot(c, (p[0] + p[1] + p[2]) * (1.0f / 3.0f) - centre) < 0.0f) {
      std::swap(p[1], p[2]);
      std::swap(n[1], n[2]);
    }
    out.add_triangle(p[0], p[1], p[2], n[0], n[1], n[2], material, emitter);
  };
  for (int r = 0; r < kRings; ++r)
    for (int s = 0; s < kSeg; ++s) {
      const Vec3 a = unit(r, s), b = unit(r, s + 1), c = unit(r + 1, s), d = unit(r + 1, s + 1);
      if (r > 0) emit(a, b, d);           // the top ring's quads collapse to one triangle
      if (r < kRings - 1) emit(a, d, c);  // and so do the bottom ring's
    }
}

}  // namespace

void RasterScene::add_triangle(Vec3 p0, Vec3 p1, Vec3 p2, Vec3 n0, Vec3 n1, Vec3 n2, int32_t material,
                               int32_t emitter) {
  const Vec3 c = cross(p1 - p0, p2 - p0);
  if (!(length_squared(c) > 0.0f)) return;
  for (Vec3 p : {p0, p1, p2}) {
    positions_.push_back(p);
    bounds_.extend(p);
  }
  normals_.insert(normals_.end(), {n0, n1, n2});
  geometric_normals_.push_back(normalize(c));
  materials_.push_back(material);
  emitters_.push_back(emitter);
}

RasterScene RasterScene::build(const Scene& scene, Layer layer) {
  RasterScene out;
  const EmbreeScene& surfaces = scene.surfaces();
  for (uint32_t g = 0; g < uint32_t(surfaces.geometry_count()); ++g) {
    const int32_t m = material_index(scene, g);
    const Bsdf& bsdf = scene.materials()[size_t(m)].bsdf;
    // Null surfaces are invisible to the path tracer's camera and shadow rays alike.
    if (std::holds_alternative<NullBsdf>(bsdf)) continue;
    const bool glass = std::holds_alternative<DielectricBsdf>(bsdf);
    if ((layer == Layer::opaque && glass) || (layer == Layer::glass && !glass)) continue;
    const int32_t emitter = scene.geometry_light(g);
    if (surfaces.is_sphere(g))
      add_sphere(out, surfaces.sphere(g), m, emitter);
    else
      add_mesh(out, surfaces.mesh(g), m, emitter);
  }
  return out;
}

}  // namespace caligo
