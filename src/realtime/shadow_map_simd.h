// Shadow-map lookups for 8 points at once (xsimd, AVX2), for the SIMD passes. Kept apart
// from shadow_map.h so that only SIMD code includes xsimd. Same arithmetic, in the same
// order, as ShadowMap::visibility; a caller compiled with FMA contraction may round a point
// that sits exactly on a texel boundary differently (tests allow 0.1 % of points).
#pragma once

#include <immintrin.h>
#include <xsimd/xsimd.hpp>

#include <algorithm>

#include "realtime/shadow_map.h"

namespace caligo {

namespace shadow_detail {

// One face's lookup; `clamp` keeps rim points of a cube face inside it instead of lit.
inline xsimd::batch<float> face_visibility(const ShadowMap& map, int face, const xsimd::batch<float>& px,
                                           const xsimd::batch<float>& py, const xsimd::batch<float>& pz,
                                           bool clamp) {
  using B = xsimd::batch<float>;
  using I = xsimd::batch<int32_t>;
  const View& v = map.faces[size_t(face)];
  const Plane& d = map.depth[size_t(face)];
  const B dx = px - B(v.eye.x), dy = py - B(v.eye.y), dz = pz - B(v.eye.z);
  const B z = dx * B(v.forward.x) + dy * B(v.forward.y) + dz * B(v.forward.z);
  const B xr = dx * B(v.right.x) + dy * B(v.right.y) + dz * B(v.right.z);
  const B yu = dx * B(v.up.x) + dy * B(v.up.y) + dz * B(v.up.z);
  const float w = float(v.resolution.x), h = float(v.resolution.y);
  B ndc_x, ndc_y, texel;
  xsimd::batch_bool<float> valid(true);
  if (v.projection == Projection::perspective) {
    const B inv = B(1.0f) / (z * B(v.tan_half_fov_y));
    ndc_x = xr * inv / B(v.aspect);
    ndc_y = yu * inv;
    texel = z * B(2.0f * v.tan_half_fov_y / h);
    valid = z > B(0.0f);
  } else {
    ndc_x = xr / B(v.half_width);
    ndc_y = yu / B(v.half_height);
    texel = B(2.0f * v.half_height / h);
  }
  const B sx = (ndc_x + B(1.0f)) * B(0.5f) * B(w);
  const B sy = (B(1.0f) - ndc_y) * B(0.5f) * B(h);
  B fx, fy;
  if (clamp) {
    fx = xsimd::select(valid, xsimd::clip(xsimd::floor(sx), B(0.0f), B(w - 1.0f)), B(0.0f));
    fy = xsimd::select(valid, xsimd::clip(xsimd::floor(sy), B(0.0f), B(h - 1.0f)), B(0.0f));
  } else {
    valid = valid & (sx >= B(0.0f)) & (sx < B(w)) & (sy >= B(0.0f)) & (sy < B(h));
    fx = xsimd::select(valid, xsimd::floor(sx), B(0.0f));
    fy = xsimd::select(valid, xsimd::floor(sy), B(0.0f));
  }
  const I index = xsimd::to_int(fy) * I(d.width) + xsimd::to_int(fx);
  // The AVX2 gather instruction: xsimd 8.1's batch::gather is a scalar loop.
  const B stored(_mm256_i32gather_ps(d.data.data(), index, 4));
  const auto lit = z <= stored + (B(map.bias) + B(map.texel_bias) * texel);
  return xsimd::select(lit | !valid, B(1.0f), B(0.0f));
}

// face_visibility's bilinear 2 x 2 filter (ShadowMap::surface_visibility, same arithmetic).
inline xsimd::batch<float> filtered_face_visibility(const ShadowMap& map, int face, const xsimd::batch<float>& px,
                                                    const xsimd::batch<float>& py, const xsimd::batch<float>& pz,
                                                    bool cube) {
  using B = xsimd::batch<float>;
  using I = xsimd::batch<int32_t>;
  const View& v = map.faces[size_t(face)];
  const Plane& d = map.depth[size_t(face)];
  const B dx = px - B(v.eye.x), dy = py - B(v.eye.y), dz = pz - B(v.eye.z);
  const B z = dx * B(v.forward.x) + dy * B(v.forward.y) + dz * B(v.forward.z);
  const B xr = dx * B(v.right.x) + dy * B(v.right.y) + dz * B(v.right.z);
  const B yu = dx * B(v.up.x) + dy * B(v.up.y) + dz * B(v.up.z);
  const float w = float(v.resolution.x), h = float(v.resolution.y);
  B ndc_x, ndc_y, texel;
  xsimd::batch_bool<float> lit_anyway(false);
  if (v.projection == Projection::perspective) {
    const B inv = B(1.0f) / (z * B(v.tan_half_fov_y));
    ndc_x = xr * inv / B(v.aspect);
    ndc_y = yu * inv;
    texel = z * B(2.0f * v.tan_half_fov_y / h);
    lit_anyway = !(z > B(0.0f));
  } else {
    ndc_x = xr / B(v.half_width);
    ndc_y = yu / B(v.half_height);
    texel = B(2.0f * v.half_height / h);
  }
  const B sx = (ndc_x + B(1.0f)) * B(0.5f) * B(w);
  const B sy = (B(1.0f) - ndc_y) * B(0.5f) * B(h);
  if (!cube) lit_anyway = lit_anyway | !((sx >= B(0.0f)) & (sx < B(w)) & (sy >= B(0.0f)) & (sy < B(h)));
  const B slack = B(map.bias) + B(map.texel_bias) * texel;
  const B gx = xsimd::select(lit_anyway, B(0.0f), sx - B(0.5f)), gy = xsimd::select(lit_anyway, B(0.0f), sy - B(0.5f));
  const B x0 = xsimd::floor(gx), y0 = xsimd::floor(gy);
  const B tx = gx - x0, ty = gy - y0;
  const auto tap = [&](const B& x, const B& y) {
    B cx = x, cy = y;
    xsimd::batch_bool<float> outside(false);
    if (cube) {
      cx = xsimd::clip(x, B(0.0f), B(w - 1.0f));
      cy = xsimd::clip(y, B(0.0f), B(h - 1.0f));
    } else {
      outside = (x < B(0.0f)) | (x >= B(w)) | (y < B(0.0f)) | (y >= B(h));
      cx = xsimd::select(outside, B(0.0f), x);
      cy = xsimd::select(outside, B(0.0f), y);
    }
    const I index = xsimd::to_int(cy) * I(d.width) + xsimd::to_int(cx);
    const B stored(_mm256_i32gather_ps(d.data.data(), index, 4));
    return xsimd::select((z <= stored + slack) | outside, B(1.0f), B(0.0f));
  };
  const B x1 = x0 + B(1.0f), y1 = y0 + B(1.0f);
  const B t00 = tap(x0, y0), t10 = tap(x1, y0), t01 = tap(x0, y1), t11 = tap(x1, y1);
  const B top = t00 + tx * (t10 - t00);
  const B bottom = t01 + tx * (t11 - t01);
  return xsimd::select(lit_anyway, B(1.0f), top + ty * (bottom - top));
}

// The cube face every lane would pick (ShadowMap::face_index), or -1 when they differ.
inline int common_cube_face(const ShadowMap& map, const xsimd::batch<float>& px,
                            const xsimd::batch<float>& py, const xsimd::batch<float>& pz) {
  using B = xsimd::batch<float>;
  const Vec3 e = map.faces[0].eye;
  const B dx = px - B(e.x), dy = py - B(e.y), dz = pz - B(e.z);
  const B ax = xsimd::abs(dx), ay = xsimd::abs(dy), az = xsimd::abs(dz);
  const auto x_major = (ax >= ay) & (ax >= az);
  const auto not_x = !x_major;
  const auto y_major = not_x & (ay >= az);
  const auto not_y = !y_major;
  const auto z_major = not_x & not_y;
  const B zero(0.0f);
  if (xsimd::all(x_major & (dx >= zero))) return 0;
  if (xsimd::all(x_major & (dx < zero))) return 1;
  if (xsimd::all(y_major & (dy >= zero))) return 2;
  if (xsimd::all(y_major & (dy < zero))) return 3;
  if (xsimd::all(z_major & (dz >= zero))) return 4;
  if (xsimd::all(z_major & (dz < zero))) return 5;
  return -1;
}

// The cascade every lane would pick (ShadowMap::Cascades::face), or -1 when they differ.
inline int common_cascade(const ShadowMap& map, const xsimd::batch<float>& px, const xsimd::batch<float>& py,
                          const xsimd::batch<float>& pz) {
  using B = xsimd::batch<float>;
  const ShadowMap::Cascades& c = *map.cascades;
  const B depth = (px - B(c.eye.x)) * B(c.forward.x) + (py - B(c.eye.y)) * B(c.forward.y) +
                  (pz - B(c.eye.z)) * B(c.forward.z);
  alignas(32) float d[B::size];
  depth.store_aligned(d);
  float lo = d[0], hi = d[0];
  for (size_t i = 1; i < B::size; ++i) lo = std::min(lo, d[i]), hi = std::max(hi, d[i]);
  const int face = c.face(lo);
  return c.face(hi) == face ? face : -1;
}

// The face every lane would pick (ShadowMap::face_index), or -1 when they differ.
inline int common_face(const ShadowMap& map, const xsimd::batch<float>& px, const xsimd::batch<float>& py,
                       const xsimd::batch<float>& pz) {
  if (map.single_face()) return 0;
  if (map.cascades) return common_cascade(map, px, py, pz);
  return common_cube_face(map, px, py, pz);
}

}  // namespace shadow_detail

// The lookups of one ray o + t d in a single-face map, prepared once per ray: the face's
// depth and texel coordinates of a point on the ray are affine in t for an orthographic face
// (directional and box lights) and affine over affine for a perspective one (spot lights),
// so a batch of samples needs three multiply-adds (and one division) instead of a point,
// three dot products and two divisions. The same lookup as face_visibility up to rounding
// (a sample exactly on a texel boundary may round to the other texel).
class ShadowRaySimd {
 public:
  using B = xsimd::batch<float>;
  using I = xsimd::batch<int32_t>;
  // False for cube maps and cascades (their face changes along the ray): use
  // shadow_visibility then.
  static bool applies(const ShadowMap& map) { return map.single_face(); }

  ShadowRaySimd(const ShadowMap& map, Vec3 origin, Vec3 dir) : map_(&map) {
    const View& v = map.faces[0];
    const Plane& d = map.depth[0];
    data_ = d.data.data();
    width_ = d.width;
    w_ = float(v.resolution.x);
    h_ = float(v.resolution.y);
    perspective_ = v.projection == Projection::perspective;
    // In double: the coefficients are rounded once, to float, per ray.
    const double ox = double(origin.x) - v.eye.x, oy = double(origin.y) - v.eye.y,
                 oz = double(origin.z) - v.eye.z;
    auto along = [&](Vec3 axis, double& at0, double& per_t) {
      at0 = ox * axis.x + oy * axis.y + oz * axis.z;
      per_t = double(dir.x) * axis.x + double(dir.y) * axis.y + double(dir.z) * axis.z;
    };
    double z0, zt, x0, xt, y0, yt;
    along(v.forward, z0, zt);
    along(v.right, x0, xt);
    along(v.up, y0, yt);
    // Pixel coordinates: sx = w/2 (1 + ndc_x), sy = h/2 (1 - ndc_y).
    const double kx =
        perspective_ ? 0.5 * w_ / (double(v.tan_half_fov_y) * v.aspect) : 0.5 * w_ / v.half_width;
    const double ky = perspective_ ? -0.5 * h_ / double(v.tan_half_fov_y) : -0.5 * h_ / v.half_height;
    z0_ = float(z0), zt_ = float(zt);
    x0_ = float(x0 * kx), xt_ = float(xt * kx);
    y0_ = float(y0 * ky), yt_ = float(yt * ky);
    if (!perspective_) {  // fold the centre offsets in
      x0_ = float(x0 * kx + 0.5 * w_);
      y0_ = float(y0 * ky + 0.5 * h_);
    }
    texel_ = perspective_ ? 2.0f * v.tan_half_fov_y / h_ : 2.0f * v.half_height / h_;
    slack_ = map.bias;
  }

  // face_visibility(map, 0, o + t d, clamp = false) per lane.
  B visibility(const B& t) const {
    const B z = xsimd::fma(t, B(zt_), B(z0_));
    B sx, sy, slack;
    xsimd::batch_bool<float> valid(true);
    if (perspective_) {
      const B inv = B(1.0f) / z;
      sx = xsimd::fma(xsimd::fma(t, B(xt_), B(x0_)), inv, B(0.5f * w_));
      sy = xsimd::fma(xsimd::fma(t, B(yt_), B(y0_)), inv, B(0.5f * h_));
      slack = xsimd::fma(z, B(map_->texel_bias * texel_), B(slack_));
      valid = z > B(0.0f);
    } else {
      sx = xsimd::fma(t, B(xt_), B(x0_));
      sy = xsimd::fma(t, B(yt_), B(y0_));
      slack = B(slack_ + map_->texel_bias * texel_);
    }
    valid = valid & (sx >= B(0.0f)) & (sx < B(w_)) & (sy >= B(0.0f)) & (sy < B(h_));
    const B fx = xsimd::select(valid, xsimd::floor(sx), B(0.0f));
    const B fy = xsimd::select(valid, xsimd::floor(sy), B(0.0f));
    const I index = xsimd::to_int(fy) * I(width_) + xsimd::to_int(fx);
    const B stored(_mm256_i32gather_ps(data_, index, 4));
    const auto lit = z <= stored + slack;
    return xsimd::select(lit | !valid, B(1.0f), B(0.0f));
  }

  // The texels visibility(t) reads, clamped into the face (for cache hints).
  I texels(const B& t) const {
    B sx, sy;
    if (perspective_) {
      const B inv = B(1.0f) / xsimd::max(xsimd::fma(t, B(zt_), B(z0_)), B(1e-6f));
      sx = xsimd::fma(xsimd::fma(t, B(xt_), B(x0_)), inv, B(0.5f * w_));
      sy = xsimd::fma(xsimd::fma(t, B(yt_), B(y0_)), inv, B(0.5f * h_));
    } else {
      sx = xsimd::fma(t, B(xt_), B(x0_));
      sy = xsimd::fma(t, B(yt_), B(y0_));
    }
    const B fx = xsimd::clip(xsimd::floor(sx), B(0.0f), B(w_ - 1.0f));
    const B fy = xsimd::clip(xsimd::floor(sy), B(0.0f), B(h_ - 1.0f));
    return xsimd::batch_cast<int32_t>(fy) * I(width_) + xsimd::batch_cast<int32_t>(fx);
  }
  const float* data() const { return data_; }

 private:
  const ShadowMap* map_;
  const float* data_;
  int width_ = 0;
  float w_ = 0.0f, h_ = 0.0f;
  bool perspective_ = false;
  float z0_ = 0.0f, zt_ = 0.0f, x0_ = 0.0f, xt_ = 0.0f, y0_ = 0.0f, yt_ = 0.0f;
  float texel_ = 0.0f, slack_ = 0.0f;
};

// 1 where lit, 0 in shadow, per lane. Single-face maps, and cube maps and cascades where all
// 8 points fall in one face (the usual case for neighbouring pixels), are projected and
// gathered in SIMD; other lookups fall back to the scalar one lane by lane.
inline xsimd::batch<float> shadow_visibility(const ShadowMap& map, const xsimd::batch<float>& px,
                                             const xsimd::batch<float>& py, const xsimd::batch<float>& pz) {
  using B = xsimd::batch<float>;
  const int face = shadow_detail::common_face(map, px, py, pz);
  if (face >= 0) return shadow_detail::face_visibility(map, face, px, py, pz, map.is_cube());
  alignas(32) float x[B::size], y[B::size], z[B::size], out[B::size];
  px.store_aligned(x);
  py.store_aligned(y);
  pz.store_aligned(z);
  for (size_t i = 0; i < B::size; ++i) out[i] = map.visibility({x[i], y[i], z[i]});
  return B::load_aligned(out);
}

// ShadowMap::surface_visibility per lane, as shadow_visibility is visibility.
inline xsimd::batch<float> surface_shadow_visibility(const ShadowMap& map, const xsimd::batch<float>& px,
                                                     const xsimd::batch<float>& py, const xsimd::batch<float>& pz) {
  using B = xsimd::batch<float>;
  if (!map.filter_surfaces) return shadow_visibility(map, px, py, pz);
  const int face = shadow_detail::common_face(map, px, py, pz);
  if (face >= 0) return shadow_detail::filtered_face_visibility(map, face, px, py, pz, map.is_cube());
  alignas(32) float x[B::size], y[B::size], z[B::size], out[B::size];
  px.store_aligned(x);
  py.store_aligned(y);
  pz.store_aligned(z);
  for (size_t i = 0; i < B::size; ++i) out[i] = map.surface_visibility({x[i], y[i], z[i]});
  return B::load_aligned(out);
}

}  // namespace caligo
