// Transmittance of 8 straight segments at once through a VolumeScene (xsimd, AVX2), for
// the SIMD surface shading: media.h's segment_optical_depth over batches. Primitives with a
// constant density field (noise aside: transmittance uses the mean density, as media.h does)
// are intersected lane-parallel in object space; radial-falloff primitives call media.h's
// scalar quadrature lane by lane, so both paths share one definition of those fields.
// Kept apart from media.h so that only SIMD code includes xsimd.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <xsimd/xsimd.hpp>

#include "realtime/media.h"

namespace caligo {

class SegmentMediaBatch {
 public:
  using B = xsimd::batch<float>;
  using Mask = xsimd::batch_bool<float>;

  explicit SegmentMediaBatch(const VolumeScene& volumes) {
    for (const VolumePrimitive& prim : volumes.primitives()) {
      if (!has_constant_field(prim)) {
        scalar_.push_back({&prim, volume_bounds(prim.shape)});
        continue;
      }
      Homogeneous h;
      static_cast<ObjectSpaceShape&>(h) = object_space_shape(prim.shape);
      h.bounds = volume_bounds(prim.shape);
      h.sigma_t = (prim.shader.sigma_a + prim.shader.sigma_s) * prim.shader.density;
      homogeneous_.push_back(h);
    }
  }

  bool empty() const { return homogeneous_.empty() && scalar_.empty(); }
  size_t size() const { return homogeneous_.size() + scalar_.size(); }

  // How one primitive meets a family of segments, known ahead (per screen tile) so that the
  // lanes skip primitives the segments miss and the intersection of those they lie inside.
  enum class Overlap : uint8_t { none, whole, partial };

  // For each primitive (size() entries): how it meets every segment that starts in the
  // world box `a` and ends in the world box `b` (conservative: `partial` when unsure).
  // The segments lie in the convex hull of a and b, inside the box around both.
  void classify(const Bounds3& a, const Bounds3& b, Overlap* out) const {
    Bounds3 hull = a;
    hull.extend(b);
    size_t k = 0;
    for (const Homogeneous& h : homogeneous_)
      out[k++] = !overlaps(hull, h.bounds)        ? Overlap::none
                 : h.contains(a) && h.contains(b) ? Overlap::whole
                                                  : Overlap::partial;
    for (const Scalar& s : scalar_) out[k++] = overlaps(hull, s.bounds) ? Overlap::partial : Overlap::none;
  }

  // exp(-optical depth) per channel of the segments a -> b in the lanes of `m` (1 elsewhere).
  // `overlaps` (size() entries, from classify) or null: test every primitive.
  void transmittance(const B& ax, const B& ay, const B& az, const B& bx, const B& by, const B& bz, Mask m,
                     const Overlap* overlaps, B& r, B& g, B& b) const {
    B tr(0.0f), tg(0.0f), tb(0.0f);
    bool any = false;
    B len;
    for (size_t k = 0; k < homogeneous_.size(); ++k) {
      const Overlap o = overlaps ? overlaps[k] : Overlap::partial;
      if (o == Overlap::none) continue;
      if (!any) {
        const B dx = bx - ax, dy = by - ay, dz = bz - az;
        len = xsimd::sqrt(dx * dx + dy * dy + dz * dz);
        any = true;
      }
      const Homogeneous& h = homogeneous_[k];
      const B l = o == Overlap::whole ? len : h.overlap_fraction(ax, ay, az, bx, by, bz) * len;
      tr += B(h.sigma_t.r) * l, tg += B(h.sigma_t.g) * l, tb += B(h.sigma_t.b) * l;
    }
    for (size_t k = 0; k < scalar_.size(); ++k) {
      if (overlaps && overlaps[homogeneous_.size() + k] == Overlap::none) continue;
      add_scalar(*scalar_[k].primitive, ax, ay, az, bx, by, bz, m, tr, tg, tb);
      any = true;
    }
    if (!any) {
      r = g = b = B(1.0f);
      return;
    }
    r = xsimd::select(m, xsimd::exp(-tr), B(1.0f));
    g = xsimd::select(m, xsimd::exp(-tg), B(1.0f));
    b = xsimd::select(m, xsimd::exp(-tb), B(1.0f));
  }

 private:
  // A constant-density primitive: world -> object affine rows and its object-space shape.
  struct Homogeneous : ObjectSpaceShape {
    RGB sigma_t;     // (sigma_a + sigma_s) x density
    Bounds3 bounds;  // world

    // Does the convex shape hold the whole world box? Its object-space bounding box (centre
    // and half extent through |M|) is tested, shrunk by a relative 1e-5 against rounding.
    bool contains(const Bounds3& w) const {
      if (w.empty() || !std::isfinite(w.lo.x + w.lo.y + w.lo.z + w.hi.x + w.hi.y + w.hi.z)) return false;
      const Vec3 c = w.center(), e = w.diagonal() * 0.5f;
      Vec3 oc, oe;
      for (int r = 0; r < 3; ++r) {
        oc[r] = m[r][0] * c.x + m[r][1] * c.y + m[r][2] * c.z + m[r][3];
        oe[r] = std::abs(m[r][0]) * e.x + std::abs(m[r][1]) * e.y + std::abs(m[r][2]) * e.z;
      }
      if (sphere) {
        // The farthest corner of the object box from the centre.
        const Vec3 far{std::abs(oc.x) + oe.x, std::abs(oc.y) + oe.y, std::abs(oc.z) + oe.z};
        return length_squared(far) <= 1.0f - 1e-5f;
      }
      for (int r = 0; r < 3; ++r) {
        const float slack = 1e-5f * (hi[r] - lo[r]);
        if (!(oc[r] - oe[r] >= lo[r] + slack && oc[r] + oe[r] <= hi[r] - slack)) return false;
      }
      return true;
    }

    // Fraction in [0, 1] of the segment a -> b inside the primitive: the segment parameter
    // is the same in world and object space (the map is affine).
    B overlap_fraction(const B& ax, const B& ay, const B& az, const B& bx, const B& by, const B& bz) const {
      const B oax = ax * m[0][0] + ay * m[0][1] + az * m[0][2] + m[0][3];
      const B oay = ax * m[1][0] + ay * m[1][1] + az * m[1][2] + m[1][3];
      const B oaz = ax * m[2][0] + ay * m[2][1] + az * m[2][2] + m[2][3];
      const B obx = bx * m[0][0] + by * m[0][1] + bz * m[0][2] + m[0][3];
      const B oby = bx * m[1][0] + by * m[1][1] + bz * m[1][2] + m[1][3];
      const B obz = bx * m[2][0] + by * m[2][1] + bz * m[2][2] + m[2][3];
      const B d[3] = {obx - oax, oby - oay, obz - oaz}, o[3] = {oax, oay, oaz};
      B s0(0.0f), s1(1.0f);
      if (sphere) {
        // Closest-approach form of the discriminant (as core/ray_solids.cpp's
        // sphere_roots): far less cancellation than b^2 - ac for long segments.
        const B qa = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        const B qb = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
        const B inv = B(1.0f) / xsimd::max(qa, B(1e-30f));
        const B sc = qb * inv;
        const B lx = o[0] - d[0] * sc, ly = o[1] - d[1] * sc, lz = o[2] - d[2] * sc;
        const B h2 = B(1.0f) - (lx * lx + ly * ly + lz * lz);  // squared half chord in object units
        const B half = xsimd::sqrt(xsimd::max(h2, B(0.0f)) * inv);
        s0 = xsimd::max(s0, -sc - half);
        s1 = xsimd::min(s1, -sc + half);
        return xsimd::select((h2 >= B(0.0f)) & (qa > B(0.0f)), xsimd::max(s1 - s0, B(0.0f)), B(0.0f));
      }
      for (int a = 0; a < 3; ++a) {
        // A tiny denominator instead of 0 keeps every lane finite (no inf * 0).
        const B dd = xsimd::select(xsimd::abs(d[a]) < B(1e-20f), B(1e-20f), d[a]);
        const B inv = B(1.0f) / dd;
        const B tn = (B(lo[a]) - o[a]) * inv, tf = (B(hi[a]) - o[a]) * inv;
        s0 = xsimd::max(s0, xsimd::min(tn, tf));
        s1 = xsimd::min(s1, xsimd::max(tn, tf));
      }
      return xsimd::max(s1 - s0, B(0.0f));
    }
  };

  struct Scalar {
    const VolumePrimitive* primitive;
    Bounds3 bounds;
  };

  static bool overlaps(const Bounds3& a, const Bounds3& b) {
    return a.lo.x <= b.hi.x && a.hi.x >= b.lo.x && a.lo.y <= b.hi.y && a.hi.y >= b.lo.y && a.lo.z <= b.hi.z &&
           a.hi.z >= b.lo.z;
  }

  // media.h's interval and quadrature for a primitive the lanes do not integrate.
  static void add_scalar(const VolumePrimitive& prim, const B& ax, const B& ay, const B& az, const B& bx,
                         const B& by, const B& bz, Mask m, B& tr, B& tg, B& tb) {
    alignas(32) float add[3][B::size] = {};
    for (size_t i = 0; i < B::size; ++i) {
      if (!m.get(i)) continue;
      const Vec3 a{ax.get(i), ay.get(i), az.get(i)}, b{bx.get(i), by.get(i), bz.get(i)};
      const float len = distance(a, b);
      if (!(len > 0.0f)) continue;
      const Ray ray{a, (b - a) / len, 0.0f, len};
      const RGB tau = primitive_segment_optical_depth(prim, ray);
      add[0][i] = tau.r, add[1][i] = tau.g, add[2][i] = tau.b;
    }
    tr += B::load_aligned(add[0]), tg += B::load_aligned(add[1]), tb += B::load_aligned(add[2]);
  }

  std::vector<Homogeneous> homogeneous_;
  std::vector<Scalar> scalar_;
};

}  // namespace caligo
