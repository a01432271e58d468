// Shadow-map lookups for 8 points at once (xsimd, AVX2), for the SIMD passes. Kept apart
// from shadow_map.h so that only SIMD code includes xsimd. Same arithmetic, in the same
// order, as ShadowMap::visibility; a caller compiled with FMA contraction may round a point
// that sits exactly on a texel boundary differently (tests allow 0.1 % of points).
#pragma once

#include <immintrin.h>
#include <xsimd/xsimd.hpp>

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

}  // namespace shadow_detail

// 1 where lit, 0 in shadow, per lane. Single-face maps, and cube maps where all 8 points
// fall in one face (the usual case for neighbouring pixels), are projected and gathered in
// SIMD; other cube lookups fall back to the scalar one lane by lane.
inline xsimd::batch<float> shadow_visibility(const ShadowMap& map, const xsimd::batch<float>& px,
                                             const xsimd::batch<float>& py, const xsimd::batch<float>& pz) {
  using B = xsimd::batch<float>;
  if (map.faces.size() == 1) return shadow_detail::face_visibility(map, 0, px, py, pz, false);
  const int face = shadow_detail::common_cube_face(map, px, py, pz);
  if (face >= 0) return shadow_detail::face_visibility(map, face, px, py, pz, true);
  alignas(32) float x[B::size], y[B::size], z[B::size], out[B::size];
  px.store_aligned(x);
  py.store_aligned(y);
  pz.store_aligned(z);
  for (size_t i = 0; i < B::size; ++i) out[i] = map.visibility({x[i], y[i], z[i]});
  return B::load_aligned(out);
}

}  // namespace caligo
