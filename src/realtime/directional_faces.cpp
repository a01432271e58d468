#include "realtime/directional_faces.h"

#include <algorithm>
#include <cmath>

namespace caligo {
View light_basis(Vec3 direction, int size) {
  const Vec3 a = std::abs(direction.x) < 0.9f ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  return View::orthographic_view({}, direction, normalize(cross(direction, a)), 1, 1, {size, size});
}

namespace {

// The bounds' extent along the basis' right, up and forward axes.
struct Extent {
  float lo[3] = {kInfinity, kInfinity, kInfinity}, hi[3] = {-kInfinity, -kInfinity, -kInfinity};
};

Extent extent(const Bounds3& b, const View& basis) {
  Extent e;
  for (int i = 0; i < 8; ++i) {
    const Vec3 c = b.corner(i);
    const float v[3] = {dot(c, basis.right), dot(c, basis.up), dot(c, basis.forward)};
    for (int k = 0; k < 3; ++k) e.lo[k] = std::min(e.lo[k], v[k]), e.hi[k] = std::max(e.hi[k], v[k]);
  }
  return e;
}

// The face over light-space window [x0, x1] x [y0, y1], its eye plane at light depth z0.
View face_over(const View& basis, float x0, float x1, float y0, float y1, float z0, int size) {
  const Vec3 eye = basis.right * (0.5f * (x0 + x1)) + basis.up * (0.5f * (y0 + y1)) + basis.forward * z0;
  return View::orthographic_view(eye, basis.forward, basis.up, 0.5f * (x1 - x0), 0.5f * (y1 - y0), {size, size});
}

// The bounding sphere of the camera's frustum between depths d0 and d1 (centroid of the 8
// corners and the farthest corner from it: a function of the camera's shape only, so the
// same radius whichever way the camera turns).
void slice_sphere(const View& camera, float d0, float d1, Vec3& centre, float& radius) {
  const float ty = camera.tan_half_fov_y, tx = ty * camera.aspect;
  Vec3 corners[8];
  centre = Vec3(0.0f);
  for (int i = 0; i < 8; ++i) {
    const float d = (i & 4) ? d1 : d0;
    const float sx = (i & 1) ? 1.0f : -1.0f, sy = (i & 2) ? 1.0f : -1.0f;
    corners[i] = camera.eye + (camera.forward + camera.right * (sx * tx) + camera.up * (sy * ty)) * d;
    centre += corners[i] * 0.125f;
  }
  radius = 0.0f;
  for (const Vec3& c : corners) radius = std::max(radius, length(c - centre));
}

}  // namespace

View fit_directional_face(const Bounds3& b, Vec3 direction, int size) {
  const View basis = light_basis(direction, size);
  const Extent e = extent(b, basis);
  const float margin = 1e-3f * std::max(1e-3f, length(b.diagonal()));
  return face_over(basis, e.lo[0] - margin, e.hi[0] + margin, e.lo[1] - margin, e.hi[1] + margin, e.lo[2] - margin,
                   size);
}

void end_with_whole_face(CascadeFaces& fit, const View& whole) {
  const auto texel = [](const View& v) { return 2.0f * std::max(v.half_width, v.half_height) / float(v.resolution.x); };
  size_t keep = 0;
  while (keep < fit.faces.size() && texel(fit.faces[keep]) < texel(whole)) ++keep;
  if (keep == fit.faces.size()) return;
  const float far = fit.far.back();
  const float cx = dot(whole.eye, whole.right), cy = dot(whole.eye, whole.up);
  fit.faces.resize(keep);
  fit.far.resize(keep);
  fit.needed.resize(keep);
  fit.faces.push_back(whole);
  fit.far.push_back(far);
  fit.needed.push_back({cx - whole.half_width, cx + whole.half_width, cy - whole.half_height, cy + whole.half_height});
}

bool covers(const View& face, const CascadeFaces::Window& w) {
  if (!(w.x1 > w.x0 && w.y1 > w.y0)) return true;  // nothing of the scene to cover
  const float cx = dot(face.eye, face.right), cy = dot(face.eye, face.up);
  return w.x0 >= cx - face.half_width && w.x1 <= cx + face.half_width && w.y0 >= cy - face.half_height &&
         w.y1 <= cy + face.half_height;
}

std::vector<float> cascade_splits(float near, float far, int count, float lambda) {
  std::vector<float> ends;
  for (int i = 1; i <= count; ++i) {
    const float f = float(i) / float(count);
    const float logarithmic = near * std::pow(far / near, f), uniform = near + (far - near) * f;
    ends.push_back(lambda * logarithmic + (1.0f - lambda) * uniform);
  }
  ends.back() = far;
  return ends;
}

CascadeFaces fit_cascades(const View& camera, float near, float far, Vec3 direction, const Bounds3& scene,
                          int count, int size) {
  // Mostly logarithmic, so texels follow the perspective: at 0.75 the uniform part gave the
  // first cascade of a 200 m scene 14 m and 6 cm texels at 512, at 0.9 it has 7 m and 2 cm.
  constexpr float kLambda = 0.9f;
  constexpr float kMargin = 0.25f;  // of the sphere's radius: how far the camera may move
  const View basis = light_basis(direction, size);
  const Extent e = extent(scene, basis);
  const float slack = 1e-3f * std::max(1e-3f, length(scene.diagonal()));
  CascadeFaces out;
  out.far = cascade_splits(near, far, count, kLambda);
  float d0 = near;
  for (float d1 : out.far) {
    Vec3 centre;
    float r;
    slice_sphere(camera, d0, d1, centre, r);
    const float half = r * (1.0f + kMargin);
    // Snap to a whole number of texels no larger than the margin.
    const float texel = 2.0f * half / float(size);
    const float step = std::max(texel, std::floor(r * kMargin / texel) * texel);
    const float cx = std::round(dot(centre, basis.right) / step) * step;
    const float cy = std::round(dot(centre, basis.up) / step) * step;
    out.needed.push_back({std::max(dot(centre, basis.right) - r, e.lo[0] - slack),
                          std::min(dot(centre, basis.right) + r, e.hi[0] + slack),
                          std::max(dot(centre, basis.up) - r, e.lo[1] - slack),
                          std::min(dot(centre, basis.up) + r, e.hi[1] + slack)});
    float x0 = std::max(cx - half, e.lo[0] - slack), x1 = std::min(cx + half, e.hi[0] + slack);
    float y0 = std::max(cy - half, e.lo[1] - slack), y1 = std::min(cy + half, e.hi[1] + slack);
    if (!(x1 > x0 && y1 > y0)) {  // the slice misses the scene: nothing to shadow there
      x0 = cx - half, x1 = cx + half, y0 = cy - half, y1 = cy + half;
    }
    out.faces.push_back(face_over(basis, x0, x1, y0, y1, e.lo[2] - slack, size));
    d0 = d1;
  }
  return out;
}

}  // namespace caligo
