// The media side of the SIMD accumulation march (accumulate_simd.cpp), 8 samples per
// xsimd batch: volume primitives reduced to object-space boxes and unit spheres, the
// optical depth of the segment from each sample towards the light, phase functions and the
// noise lookup. Each re-implements media.h / phase.cpp / noise.cpp's arithmetic lane-parallel;
// accumulate_test.cpp checks the whole march against the scalar one.
//
// The light-side segment is the costly part of a sample, so it is prepared per light:
// lights with one direction everywhere (directional, box) get the reciprocal of that
// direction in each primitive's object space once, so their slab and sphere tests divide
// nothing per sample; point and spot lights get their object-space position, and a segment
// whose both ends lie inside a convex primitive (known from the camera's intervals) takes
// its whole length without a test. Internal to src/realtime.
#pragma once

#include <immintrin.h>
#include <xsimd/xsimd.hpp>

#include <cmath>

#include "realtime/media.h"

namespace caligo::lanes {

using Batch = xsimd::batch<float>;
using Mask = xsimd::batch_bool<float>;
using IBatch = xsimd::batch<int32_t>;

struct BatchVec {
  Batch x, y, z;
};
inline Batch dot(const BatchVec& a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// A volume primitive reduced to what the lanes need: world -> object affine rows, its
// shape in object space and density-scaled coefficients.
struct Primitive : ObjectSpaceShape {
  RGB sigma_t, sigma_s;
  PhaseFunction phase;
  const NoiseModulation* noise = nullptr;

  BatchVec to_object(const BatchVec& p) const {
    return {p.x * m[0][0] + p.y * m[0][1] + p.z * m[0][2] + m[0][3],
            p.x * m[1][0] + p.y * m[1][1] + p.z * m[1][2] + m[1][3],
            p.x * m[2][0] + p.y * m[2][1] + p.z * m[2][2] + m[2][3]};
  }
  BatchVec to_object_dir(const BatchVec& d) const {
    return {d.x * m[0][0] + d.y * m[0][1] + d.z * m[0][2], d.x * m[1][0] + d.y * m[1][1] + d.z * m[1][2],
            d.x * m[2][0] + d.y * m[2][1] + d.z * m[2][2]};
  }
  Vec3 to_object_dir(Vec3 d) const {
    return {d.x * m[0][0] + d.y * m[0][1] + d.z * m[0][2], d.x * m[1][0] + d.y * m[1][1] + d.z * m[1][2],
            d.x * m[2][0] + d.y * m[2][1] + d.z * m[2][2]};
  }
  Vec3 to_object(Vec3 p) const { return to_object_dir(p) + Vec3(m[0][3], m[1][3], m[2][3]); }
  bool contains_object(Vec3 q) const {
    return sphere ? length_squared(q) <= 1.0f
                  : q.x >= lo.x && q.x <= hi.x && q.y >= lo.y && q.y <= hi.y && q.z >= lo.z && q.z <= hi.z;
  }
};

// Object-space description of a primitive for the lanes; false for density fields the
// SIMD path does not integrate (radial falloff).
bool describe_primitive(const VolumePrimitive& prim, Primitive& out);

// A tiny magnitude instead of 0 keeps every reciprocal finite (no inf * 0 in the slabs).
inline float safe_reciprocal(float d) { return 1.0f / (std::abs(d) < 1e-20f ? std::copysign(1e-20f, d) : d); }
inline Batch safe_reciprocal(const Batch& d) {
  return 1.0f / xsimd::select(xsimd::abs(d) < 1e-20f, Batch(1e-20f), d);
}

// Length of { o + d s : s in [0, reach] } inside the box [lo, hi] (object space; s in the
// caller's units), given 1/d per axis.
inline Batch box_overlap(const Primitive& prim, const BatchVec& o, const BatchVec& inv, const Batch& reach) {
  const Batch oc[3] = {o.x, o.y, o.z}, ic[3] = {inv.x, inv.y, inv.z};
  Batch s0(0.0f), s1 = reach;
  for (int a = 0; a < 3; ++a) {
    const Batch tn = (prim.lo[a] - oc[a]) * ic[a], tf = (prim.hi[a] - oc[a]) * ic[a];
    s0 = xsimd::max(s0, xsimd::min(tn, tf));
    s1 = xsimd::min(s1, xsimd::max(tn, tf));
  }
  return xsimd::max(s1 - s0, Batch(0.0f));
}

// The same for the unit sphere, given |d|^2 and its reciprocal; 0 where the line misses.
inline Batch sphere_overlap(const BatchVec& o, const BatchVec& d, const Batch& qa, const Batch& inv_qa,
                            const Batch& reach) {
  const Batch qb = o.x * d.x + o.y * d.y + o.z * d.z;
  const Batch qc = o.x * o.x + o.y * o.y + o.z * o.z - 1.0f;
  const Batch disc = qb * qb - qa * qc;
  const Mask hit = disc > 0.0f;
  if (xsimd::none(hit)) return Batch(0.0f);
  const Batch root = xsimd::sqrt(xsimd::max(disc, Batch(0.0f)));
  const Batch s0 = xsimd::max(Batch(0.0f), (-qb - root) * inv_qa);
  const Batch s1 = xsimd::min(reach, (-qb + root) * inv_qa);
  return xsimd::select(hit, xsimd::max(s1 - s0, Batch(0.0f)), Batch(0.0f));
}

// One primitive as the segments towards one light cross it, prepared per light.
struct LightSide {
  // Directional and box lights: the unit direction to the light in object space and its
  // reciprocal per axis; |d|^2 and its reciprocal for spheres.
  bool parallel = false;
  Vec3 d, inv;
  float qa = 1.0f, inv_qa = 1.0f;
  // Point and spot lights: the light inside the (convex) primitive, so a segment from a
  // sample inside it lies wholly inside.
  bool light_inside = false;
  // Spheres seen from a point light outside their bounding ball: segments leaving the light
  // outside the cone (axis, cos_half) around the ball miss the sphere.
  bool cone_cull = false;
  Vec3 cone_axis;
  float cone_cos = 1.0f;

  static LightSide parallel_light(const Primitive& prim, Vec3 wi);
  static LightSide point_light(const Primitive& prim, const VolumePrimitive& source, Vec3 position);

  // Length of the segment p + wi s, s in [0, reach], inside `prim`. `inside`: the lanes
  // whose p is known to lie in the primitive (from the camera's intervals), `ok`: the lanes
  // that count.
  Batch overlap(const Primitive& prim, const BatchVec& p, const BatchVec& wi, const Batch& reach,
                const Mask& inside, const Mask& ok) const {
    if (light_inside && xsimd::all(inside | !ok)) return reach;
    if (cone_cull && xsimd::none(ok & (-dot(wi, cone_axis) >= cone_cos))) return Batch(0.0f);
    const BatchVec o = prim.to_object(p);
    if (parallel) {
      if (prim.sphere)
        return sphere_overlap(o, {Batch(d.x), Batch(d.y), Batch(d.z)}, Batch(qa), Batch(inv_qa), reach);
      return box_overlap(prim, o, {Batch(inv.x), Batch(inv.y), Batch(inv.z)}, reach);
    }
    const BatchVec od = prim.to_object_dir(wi);
    if (prim.sphere) {
      const Batch a = od.x * od.x + od.y * od.y + od.z * od.z;
      return sphere_overlap(o, od, a, 1.0f / xsimd::max(a, Batch(1e-30f)), reach);
    }
    return box_overlap(prim, o, {safe_reciprocal(od.x), safe_reciprocal(od.y), safe_reciprocal(od.z)}, reach);
  }
};

// Henyey-Greenstein written as phase.cpp's henyey_greenstein (same branch on the sign of g).
inline Batch hg(const Batch& cos_theta, float g) {
  const Batch denom = g >= 0.0f ? Batch(sqr(1.0f - g)) + (2.0f * g) * (1.0f - cos_theta)
                                : Batch(sqr(1.0f + g)) - (2.0f * g) * (1.0f + cos_theta);
  return (kInv4Pi * (1.0f - g) * (1.0f + g)) / (denom * xsimd::sqrt(denom));
}

struct PhaseBatch {
  Batch cos_theta;
  Batch operator()(const IsotropicPhase&) const { return Batch(kInv4Pi); }
  Batch operator()(const HenyeyGreensteinPhase& p) const { return hg(cos_theta, p.g); }
  Batch operator()(const SchlickPhase& p) const {
    const float k = p.k;
    const Batch denom =
        k >= 0.0f ? Batch(1.0f - k) + k * (1.0f - cos_theta) : Batch(1.0f + k) - k * (1.0f + cos_theta);
    return (kInv4Pi * (1.0f - k) * (1.0f + k)) / (denom * denom);
  }
  Batch operator()(const DoubleHenyeyGreensteinPhase& p) const {
    return p.w * hg(cos_theta, p.g1) + (1.0f - p.w) * hg(cos_theta, p.g2);
  }
};

// volumes/noise.cpp's noise_density, lane-parallel (the same arithmetic in the same order,
// with AVX2 gathers for the lattice values).
Batch noise_density_batch(const NoiseModulation& noise, const Batch& px, const Batch& py, const Batch& pz);

// e^-x for x >= 0 (optical depths): Cody-Waite reduction to 2^n e^r, |r| <= ln2/2, and a
// degree-6 polynomial for e^r; relative error below 3e-7. Underflows to 0 past x = 87.
inline Batch exp_neg(const Batch& x) {
  const Batch y = xsimd::min(x, Batch(87.0f));
  const Batch n = xsimd::nearbyint(y * -1.44269504f);
  // -y = n ln2 + rr, ln2 split in two so that n ln2 is exact in its high part.
  const Batch r = xsimd::fma(n, Batch(-0.693145751953125f), -y);
  const Batch rr = xsimd::fma(n, Batch(-1.428606765330187e-06f), r);
  Batch q = xsimd::fma(Batch(1.0f / 720.0f), rr, Batch(1.0f / 120.0f));
  q = xsimd::fma(q, rr, Batch(1.0f / 24.0f));
  q = xsimd::fma(q, rr, Batch(1.0f / 6.0f));
  q = xsimd::fma(q, rr, Batch(0.5f));
  q = xsimd::fma(q, rr, Batch(1.0f));
  q = xsimd::fma(q, rr, Batch(1.0f));
  // 2^n by building the exponent bits (n in [-126, 0]).
  const IBatch bits = (xsimd::batch_cast<int32_t>(n) + 127) << 23;
  const Batch scale = xsimd::bitwise_cast<Batch>(bits);
  return xsimd::select(x < 87.0f, q * scale, Batch(0.0f));
}

}  // namespace caligo::lanes
