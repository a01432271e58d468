// Lane-parallel (xsimd, 8 floats with -march=x86-64-v3) forms of lights/light_profile.h's
// gobo and IES lookups, for the SIMD passes (accumulation, surface shading). Each follows
// its scalar function step by step (same clamps, wraps and lerps), with AVX2 gathers for the
// texels and table entries; light_profile_simd_test.cpp checks them against the scalar
// functions to 1e-4 relative. Header-only so the calls inline into the passes' loops; the
// prepared types are built once per light and frame and are then read-only (thread-safe).
#pragma once

#include <immintrin.h>
#include <xsimd/xsimd.hpp>

#include <cmath>
#include <cstdint>

#include "core/math.h"
#include "lights/gobo.h"
#include "lights/ies.h"
#include "lights/light.h"

namespace caligo {

namespace profile_simd {

using B = xsimd::batch<float>;
using I = xsimd::batch<int32_t>;

// xsimd 8.1's batch::gather is a scalar loop; this is the AVX2 instruction.
inline B gather(const float* base, const I& index) { return B(_mm256_i32gather_ps(base, index, 4)); }

inline B lerp(const B& t, const B& a, const B& b) { return (1.0f - t) * a + t * b; }

// Index i with table[i] <= x <= table[i + 1] and the weight of table[i + 1] (ies.cpp's
// bracket, x inside the table): a branchless binary search per lane for upper_bound.
inline void bracket(const std::vector<float>& table, const B& x, I& index, B& weight) {
  const int n = int(table.size());
  if (n == 1) {
    index = I(0);
    weight = B(0.0f);
    return;
  }
  const float* t = table.data();
  // Indices as floats (exact below 2^24) so the float comparisons can select them.
  B base(0.0f);  // the last entry <= x, or 0 when none is
  for (int len = n; len > 1;) {
    const int half = len / 2;
    const B candidate = base + float(half);
    base = xsimd::select(gather(t, xsimd::batch_cast<int32_t>(candidate)) <= x, candidate, base);
    len -= half;
  }
  const B upper = base + xsimd::select(gather(t, xsimd::batch_cast<int32_t>(base)) <= x, B(1.0f), B(0.0f));
  index = xsimd::batch_cast<int32_t>(xsimd::min(xsimd::max(upper, B(1.0f)), B(float(n - 1))) - 1.0f);
  const B lo = gather(t, index), hi = gather(t, index + 1);
  weight = xsimd::min(xsimd::max((x - lo) / (hi - lo), B(0.0f)), B(1.0f));
}

}  // namespace profile_simd

struct RgbBatch {
  xsimd::batch<float> r, g, b;
};

// gobo_filter for one gobo: white without an image.
class GoboSampler {
 public:
  using B = profile_simd::B;
  explicit GoboSampler(const Gobo& gobo)
      : image_(gobo.image.get()),
        cos_(std::cos(gobo.rotation)),
        sin_(std::sin(gobo.rotation)),
        offset_(gobo.offset) {
    static_assert(sizeof(RGB) == 3 * sizeof(float), "gathers address RGB texels as float triples");
  }
  bool has_image() const { return image_ != nullptr; }

  // gobo_filter(gobo, (u, v)) per lane.
  RgbBatch filter(const B& u, const B& v) const {
    if (!image_) return {B(1.0f), B(1.0f), B(1.0f)};
    // Rotate about the image centre, then shift (gobo_filter).
    const B x = u - 0.5f, y = v - 0.5f;
    const B su = cos_ * x - sin_ * y + (0.5f + offset_.x);
    const B sv = sin_ * x + cos_ * y + (0.5f + offset_.y);
    return lookup(su, sv);
  }

 private:
  using I = profile_simd::I;
  // GoboImage::lookup per lane: bilinear, wrapping, 0 for non-finite coordinates.
  RgbBatch lookup(const B& su, const B& sv) const {
    const float w = float(image_->width()), h = float(image_->height());
    B x = su * w - 0.5f, y = (1.0f - sv) * h - 0.5f;
    const auto finite = (xsimd::abs(x) <= B(3.0e38f)) & (xsimd::abs(y) <= B(3.0e38f));
    x = xsimd::select(finite, x, B(0.0f));
    y = xsimd::select(finite, y, B(0.0f));
    const B fx = xsimd::floor(x), fy = xsimd::floor(y);
    const B tx = x - fx, ty = y - fy;
    const I x0 = wrap(fx, w, 1.0f / w), y0 = wrap(fy, h, 1.0f / h);
    const I x1 = xsimd::select(x0 + 1 >= I(int32_t(w)), I(0), x0 + 1);
    const I y1 = xsimd::select(y0 + 1 >= I(int32_t(h)), I(0), y0 + 1);
    const I width(image_->width());
    const I i00 = y0 * width + x0, i10 = y0 * width + x1;
    const I i01 = y1 * width + x0, i11 = y1 * width + x1;
    const B zero(0.0f);
    // Neighbours in memory (no wrap between the taps, and 8 floats readable from the first
    // tap: not the image's last two texels): one unaligned load per lane and row.
    const int texel_count = image_->width() * image_->height();
    const auto adjacent = (x1 == x0 + 1) & (i01 <= I(texel_count - 3)) & (i00 <= I(texel_count - 3));
    if (texel_count >= 3 && xsimd::all(adjacent)) {
      B top[3], bottom[3];
      row_pairs(i00, tx, top);
      row_pairs(i01, tx, bottom);
      return {xsimd::select(finite, top[0] * (1.0f - ty) + bottom[0] * ty, zero),
              xsimd::select(finite, top[1] * (1.0f - ty) + bottom[1] * ty, zero),
              xsimd::select(finite, top[2] * (1.0f - ty) + bottom[2] * ty, zero)};
    }
    const float* texels = &image_->data()->r;
    auto channel = [&](int c) {
      const B top =
          lerp_x(tx, profile_simd::gather(texels + c, i00 * 3), profile_simd::gather(texels + c, i10 * 3));
      const B bottom =
          lerp_x(tx, profile_simd::gather(texels + c, i01 * 3), profile_simd::gather(texels + c, i11 * 3));
      return xsimd::select(finite, top * (1.0f - ty) + bottom * ty, zero);
    };
    return {channel(0), channel(1), channel(2)};
  }
  // The horizontal lerp of the texel pairs starting at texel `first` of each lane, per channel:
  // 8 loads of r0 g0 b0 r1 g1 b1 (and 2 floats more), transposed into channel batches
  // (12 gathers cost about twice as much).
  void row_pairs(const I& first, const B& tx, B out[3]) const {
    alignas(32) int32_t index[8];
    (first * 3).store_aligned(index);
    const float* texels = &image_->data()->r;
    __m256 v[8];
    for (int i = 0; i < 8; ++i) v[i] = _mm256_loadu_ps(texels + index[i]);
    const __m256 t0 = _mm256_unpacklo_ps(v[0], v[1]), t1 = _mm256_unpackhi_ps(v[0], v[1]);
    const __m256 t2 = _mm256_unpacklo_ps(v[2], v[3]), t3 = _mm256_unpackhi_ps(v[2], v[3]);
    const __m256 t4 = _mm256_unpacklo_ps(v[4], v[5]), t5 = _mm256_unpackhi_ps(v[4], v[5]);
    const __m256 t6 = _mm256_unpacklo_ps(v[6], v[7]), t7 = _mm256_unpackhi_ps(v[6], v[7]);
    // Lanes 0-3 of the image's elements k (low half) and k + 4 (high half).
    const __m256 u0 = _mm256_shuffle_ps(t0, t2, 0x44), u1 = _mm256_shuffle_ps(t0, t2, 0xEE);
    const __m256 u2 = _mm256_shuffle_ps(t1, t3, 0x44), u3 = _mm256_shuffle_ps(t1, t3, 0xEE);
    const __m256 u4 = _mm256_shuffle_ps(t4, t6, 0x44), u5 = _mm256_shuffle_ps(t4, t6, 0xEE);
    const __m256 u6 = _mm256_shuffle_ps(t5, t7, 0x44), u7 = _mm256_shuffle_ps(t5, t7, 0xEE);
    const B r0(_mm256_permute2f128_ps(u0, u4, 0x20)), g0(_mm256_permute2f128_ps(u1, u5, 0x20));
    const B b0(_mm256_permute2f128_ps(u2, u6, 0x20)), r1(_mm256_permute2f128_ps(u3, u7, 0x20));
    const B g1(_mm256_permute2f128_ps(u0, u4, 0x31)), b1(_mm256_permute2f128_ps(u1, u5, 0x31));
    out[0] = lerp_x(tx, r0, r1);
    out[1] = lerp_x(tx, g0, g1);
    out[2] = lerp_x(tx, b0, b1);
  }
  static B lerp_x(const B& t, const B& a, const B& b) { return a * (1.0f - t) + b * t; }
  // wrap(int(fmod(f, n)), n) for integral f: the remainder in [0, n), with a correction for
  // the rounding of f / n at multiples of n. f * (1 / n) instead of a division: its error
  // stays below 1 / n for |f| < 2^23, so the floor can only be off at multiples of n, which
  // the correction catches (and f - n floor(.) is exact there).
  static I wrap(const B& f, float n, float inv_n) {
    B m = f - n * xsimd::floor(f * inv_n);
    m = xsimd::select(m >= n, m - n, m);
    m = xsimd::select(m < 0.0f, m + n, m);
    return xsimd::batch_cast<int32_t>(m);
  }

  const GoboImage* image_;
  float cos_, sin_;
  Vec2 offset_;
};

// spot_gobo_uv followed by gobo_filter: the gobo colour in directions leaving the light.
class SpotGoboSampler {
 public:
  using B = profile_simd::B;
  explicit SpotGoboSampler(const SpotLight& light)
      : sampler_(light.gobo),
        direction_(light.direction),
        up_(light.up),
        right_(cross(light.direction, light.up)) {
    const float tan_outer = safe_sqrt(1.0f - sqr(light.cos_outer)) / std::fmax(light.cos_outer, 1e-6f);
    tan_ = std::fmax(tan_outer, 1e-6f);
  }
  bool has_image() const { return sampler_.has_image(); }

  // spot_gobo_uv(light, w) per lane; (-1, -1) at or behind the light's plane.
  void uv(const B& wx, const B& wy, const B& wz, B& u, B& v) const {
    const B z = wx * direction_.x + wy * direction_.y + wz * direction_.z;
    const auto front = z > 1e-6f;
    const B scale = 0.5f / (xsimd::select(front, z, B(1.0f)) * tan_);
    u = xsimd::select(front, 0.5f + (wx * right_.x + wy * right_.y + wz * right_.z) * scale, B(-1.0f));
    v = xsimd::select(front, 0.5f + (wx * up_.x + wy * up_.y + wz * up_.z) * scale, B(-1.0f));
  }
  // gobo_filter(light.gobo, spot_gobo_uv(light, w)) per lane, w unit and leaving the light.
  RgbBatch filter(const B& wx, const B& wy, const B& wz) const {
    B u, v;
    uv(wx, wy, wz, u, v);
    return sampler_.filter(u, v);
  }

 private:
  GoboSampler sampler_;
  Vec3 direction_, up_, right_;
  float tan_ = 1.0f;
};

// ies_factor per lane: 1 without a profile.
class IesSampler {
 public:
  using B = profile_simd::B;
  explicit IesSampler(const IesAttachment& ies)
      : profile_(ies.profile.get()), frame_(Frame::from_z(ies.axis)) {
    if (!profile_) return;
    const std::vector<float>& h = profile_->horizontal_degrees();
    last_horizontal_ = h.back();
    single_horizontal_ = h.size() == 1;
  }
  bool has_profile() const { return profile_ != nullptr; }

  // ies_factor(ies, w) per lane, w unit and leaving the light.
  B factor(const B& wx, const B& wy, const B& wz) const {
    if (!profile_) return B(1.0f);
    using profile_simd::I;
    const B lx = wx * frame_.s.x + wy * frame_.s.y + wz * frame_.s.z;
    const B ly = wx * frame_.t.x + wy * frame_.t.y + wz * frame_.t.z;
    const B lz = wx * frame_.n.x + wy * frame_.n.y + wz * frame_.n.z;
    B vertical = xsimd::acos(xsimd::min(xsimd::max(lz, B(-1.0f)), B(1.0f)));
    B horizontal = xsimd::atan2(ly, lx);
    horizontal = xsimd::select(horizontal < 0.0f, horizontal + 2.0f * kPi, horizontal);
    vertical *= 180.0f / kPi;  // IesProfile::evaluate works in degrees
    horizontal *= 180.0f / kPi;
    const std::vector<float>& vt = profile_->vertical_degrees();
    const auto measured = (vertical >= vt.front()) & (vertical <= vt.back());
    I v, h;
    B tv, th;
    profile_simd::bracket(vt, vertical, v, tv);
    profile_simd::bracket(profile_->horizontal_degrees(), fold(horizontal), h, th);
    const int nv = int(vt.size());
    const I h1 = single_horizontal_ ? h : h + 1;
    const float* values = profile_->values().data();
    auto at = [&](const I& hi, const I& vi) { return profile_simd::gather(values, hi * nv + vi); };
    const B a = profile_simd::lerp(tv, at(h, v), at(h, v + 1));
    const B b = profile_simd::lerp(tv, at(h1, v), at(h1, v + 1));
    return xsimd::select(measured, profile_simd::lerp(th, a, b), B(0.0f));
  }

 private:
  // IesProfile::fold_horizontal for h in [0, 360] degrees (atan2's range after the shift).
  B fold(B h) const {
    if (single_horizontal_) return B(0.0f);
    h = xsimd::select(h >= 360.0f, h - 360.0f, h);
    if (last_horizontal_ == 360.0f) return h;
    h = xsimd::select(h > 180.0f, 360.0f - h, h);
    if (last_horizontal_ == 180.0f) return h;
    return xsimd::select(h > 90.0f, 180.0f - h, h);
  }

  const IesProfile* profile_;
  Frame frame_;
  float last_horizontal_ = 0.0f;
  bool single_horizontal_ = true;
};

// One-call forms for code outside inner loops (they prepare the light each call).
inline RgbBatch spot_gobo_batch(const SpotLight& light, const xsimd::batch<float>& wx,
                                const xsimd::batch<float>& wy, const xsimd::batch<float>& wz) {
  return SpotGoboSampler(light).filter(wx, wy, wz);
}
// A box light's gobo at local coordinates (x along right, y along up; delta_arrival's uv).
inline RgbBatch box_gobo_batch(const BoxLight& light, const xsimd::batch<float>& x,
                               const xsimd::batch<float>& y) {
  return GoboSampler(light.gobo)
      .filter(0.5f + 0.5f * x / light.half_width, 0.5f + 0.5f * y / light.half_height);
}
inline xsimd::batch<float> ies_batch(const IesAttachment& ies, const xsimd::batch<float>& wx,
                                     const xsimd::batch<float>& wy, const xsimd::batch<float>& wz) {
  return IesSampler(ies).factor(wx, wy, wz);
}

}  // namespace caligo
