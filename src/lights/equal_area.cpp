#include "lights/equal_area.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/math.h"
#include "lights/environment_map.h"

namespace caligo {

Vec2 equal_area_sphere_to_square(Vec3 d) {
  const float x = std::abs(d.x), y = std::abs(d.y), z = std::abs(d.z);
  const float r = std::sqrt(std::max(0.0f, 1.0f - z));  // the distance from the centre
  const float a = std::max(x, y), b = a > 0.0f ? std::min(x, y) / a : 0.0f;
  float phi = std::atan(b) * (2.0f / kPi);  // the angle within an octant, in [0, 1]
  if (x < y) phi = 1.0f - phi;
  float v = phi * r, u = r - v;
  if (d.z < 0.0f) {  // the lower hemisphere folds out into the corners
    std::swap(u, v);
    u = 1.0f - u;
    v = 1.0f - v;
  }
  return {0.5f * (std::copysign(u, d.x) + 1.0f), 0.5f * (std::copysign(v, d.y) + 1.0f)};
}

Vec3 equal_area_square_to_sphere(Vec2 p) {
  const float u = 2.0f * p.x - 1.0f, v = 2.0f * p.y - 1.0f;
  const float signed_distance = 1.0f - (std::abs(u) + std::abs(v));
  const float r = 1.0f - std::abs(signed_distance);
  const float phi = (r == 0.0f ? 1.0f : (std::abs(v) - std::abs(u)) / r + 1.0f) * (kPi / 4.0f);
  const float z = std::copysign(1.0f - r * r, signed_distance);
  const float s = r * std::sqrt(std::max(0.0f, 2.0f - r * r));
  return {std::copysign(std::cos(phi), u) * s, std::copysign(std::sin(phi), v) * s, z};
}

namespace {

// A texel of the square with the octahedral wrap: crossing an edge continues on the sphere in
// the texel mirrored about the edge's midpoint.
RGB texel(const std::vector<RGB>& square, int n, int x, int y) {
  if (x < 0 || x >= n) {
    x = x < 0 ? -1 - x : 2 * n - 1 - x;
    y = n - 1 - y;
  }
  if (y < 0 || y >= n) {
    y = y < 0 ? -1 - y : 2 * n - 1 - y;
    x = n - 1 - x;
  }
  return square[size_t(std::clamp(y, 0, n - 1)) * size_t(n) + size_t(std::clamp(x, 0, n - 1))];
}

RGB bilinear(const std::vector<RGB>& square, int n, Vec2 p) {
  const float fx = p.x * float(n) - 0.5f, fy = p.y * float(n) - 0.5f;
  const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
  const float tx = fx - float(x0), ty = fy - float(y0);
  return texel(square, n, x0, y0) * ((1 - tx) * (1 - ty)) + texel(square, n, x0 + 1, y0) * (tx * (1 - ty)) +
         texel(square, n, x0, y0 + 1) * ((1 - tx) * ty) + texel(square, n, x0 + 1, y0 + 1) * (tx * ty);
}

}  // namespace

std::vector<RGB> equal_area_to_latlong(const std::vector<RGB>& square, int n, const Transform& light_to_world) {
  const int width = 2 * n, height = n;
  std::vector<RGB> out(size_t(width) * size_t(height));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Vec3 w = latlong_to_direction({(float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height)});
      const Vec3 d = normalize(light_to_world.inverse_vector(w));
      out[size_t(y) * size_t(width) + size_t(x)] = bilinear(square, n, equal_area_sphere_to_square(d));
    }
  return out;
}

}  // namespace caligo
