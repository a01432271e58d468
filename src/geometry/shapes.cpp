#include "geometry/shapes.h"

#include <cmath>

#include "core/ray_solids.h"

namespace caligo {

TriangleMesh box_mesh(Vec3 lo, Vec3 hi) {
  TriangleMesh mesh;
  for (int i = 0; i < 8; ++i)
    mesh.positions.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  // Each face as a quad (a, b, c, d) wound counter-clockwise seen from outside.
  const uint32_t faces[6][4] = {
      {0, 4, 6, 2},  // -x
      {1, 3, 7, 5},  // +x
      {0, 1, 5, 4},  // -y
      {2, 6, 7, 3},  // +y
      {0, 2, 3, 1},  // -z
      {4, 5, 7, 6},  // +z
  };
  for (const auto& f : faces) mesh.indices.insert(mesh.indices.end(), {f[0], f[1], f[2], f[0], f[2], f[3]});
  return mesh;
}

TriangleMesh rectangle_mesh(Vec3 corner, Vec3 edge1, Vec3 edge2) {
  TriangleMesh mesh;
  mesh.positions = {corner, corner + edge1, corner + edge1 + edge2, corner + edge2};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  mesh.uvs = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};  // u along edge1, v along edge2
  return mesh;
}

Sphere Sphere::make(Vec3 center, float radius, const Transform& placement) {
  return {placement * Transform::translate(center) * Transform::scale(Vec3(radius))};
}

// The unit sphere in object space (an affine map keeps the ray parameter).
std::optional<RayRange> intersect_sphere(const Sphere& sphere, const Ray& world_ray) {
  const Transform& to_object = sphere.object_to_world;
  return sphere_roots(to_object.inverse_point(world_ray.origin), to_object.inverse_vector(world_ray.direction),
                      Vec3(0.0f), 1.0f);
}

Vec3 sphere_normal(const Sphere& sphere, Vec3 world_point) {
  const Vec3 p = sphere.object_to_world.inverse_point(world_point);
  return normalize(sphere.object_to_world.normal(p));
}

}  // namespace caligo
