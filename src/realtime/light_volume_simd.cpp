#include "realtime/light_volume_simd.h"

#include <cmath>
#include <limits>

namespace caligo {
namespace {

using Batch = LightVolumeLanes::Batch;
using Mask = LightVolumeLanes::Mask;

constexpr float kInf = std::numeric_limits<float>::infinity();
// Relative error bound of one float operation chain below (a few ulps, generously).
constexpr float kEps = 2e-6f;
// How far (relative to the magnitudes involved) an interval end may sit from the scalar
// double answer before a lane is handed to the scalar test.
constexpr float kTol = 1e-4f;

}  // namespace

LightVolumeLanes::LightVolumeLanes(const Light& light) {
  // Which test, with what constants, for each light type light_volume_interval handles.
  struct Describe {
    LightVolumeLanes& d;
    void operator()(const PointLight& l) const {
      if (!std::isfinite(l.range)) {
        d.kind_ = Kind::whole;
        return;
      }
      d.kind_ = Kind::sphere;
      d.centre_ = l.position;
      d.radius_ = l.range;
    }
    void operator()(const SpotLight& l) const {
      d.centre_ = l.position;
      d.radius_ = l.range;
      d.range_sphere_ = std::isfinite(l.range);
      if (l.cos_outer <= 0.0f) {
        // Not convex: light_volume_interval takes the whole ray (then the range sphere).
        d.kind_ = d.range_sphere_ ? Kind::sphere : Kind::whole;
        return;
      }
      d.kind_ = Kind::cone;
      d.axis_ = l.direction;
      d.cos2_ = l.cos_outer * l.cos_outer;
    }
    void operator()(const BoxLight& l) const {
      d.kind_ = Kind::box;
      d.centre_ = l.position;
      d.box_axes_[0] = cross(l.direction, l.up);
      d.box_axes_[1] = l.up;
      d.box_axes_[2] = l.direction;
      d.box_lo_[0] = -l.half_width;
      d.box_lo_[1] = -l.half_height;
      d.box_lo_[2] = 0.0f;
      d.box_hi_[0] = l.half_width;
      d.box_hi_[1] = l.half_height;
      d.box_hi_[2] = l.range;
    }
    void operator()(const DirectionalLight&) const { d.kind_ = Kind::whole; }
    void operator()(const SphereLight&) const { d.kind_ = Kind::none; }
    void operator()(const QuadLight&) const { d.kind_ = Kind::none; }
    void operator()(const TriangleLight&) const { d.kind_ = Kind::none; }
    void operator()(const EnvironmentLight&) const { d.kind_ = Kind::none; }
  };
  std::visit(Describe{*this}, light);
}

LightVolumeLanes::Result LightVolumeLanes::intervals(const Batch& ox, const Batch& oy, const Batch& oz,
                                                     const Batch& dx, const Batch& dy, const Batch& dz,
                                                     const Batch& tmax) const {
  Result r{Batch(0.0f), tmax, Mask(false), Mask(false)};
  switch (kind_) {
    case Kind::none:
      return r;
    case Kind::whole:
      r.hit = Batch(0.0f) <= tmax;
      return r;
    case Kind::sphere:
      sphere(ox, oy, oz, dx, dy, dz, tmax, r);
      return r;
    case Kind::cone: {
      cone(ox, oy, oz, dx, dy, dz, tmax, r);
      if (!range_sphere_) return r;
      Result s{Batch(0.0f), tmax, Mask(false), Mask(false)};
      sphere(ox, oy, oz, dx, dy, dz, tmax, s);
      r.t0 = xsimd::max(r.t0, s.t0);
      r.t1 = xsimd::min(r.t1, s.t1);
      r.hit = r.hit & s.hit & (r.t0 <= r.t1);
      r.unsure = r.unsure | s.unsure;
      return r;
    }
    case Kind::box:
      box(ox, oy, oz, dx, dy, dz, tmax, r);
      return r;
  }
  return r;
}

// ray_sphere_interval: relative to the closest point on the line, as the scalar test.
void LightVolumeLanes::sphere(const Batch& ox, const Batch& oy, const Batch& oz, const Batch& dx,
                              const Batch& dy, const Batch& dz, const Batch& tmax, Result& r) const {
  const Batch cx = ox - centre_.x, cy = oy - centre_.y, cz = oz - centre_.z;
  const Batch b = cx * dx + cy * dy + cz * dz;
  const Batch qx = cx - dx * b, qy = cy - dy * b, qz = cz - dz * b;
  const float r2 = radius_ * radius_;
  const Batch h = r2 - (qx * qx + qy * qy + qz * qz);
  // Near-tangent lines: the chord's half length sqrt(h) is ill-conditioned in float.
  r.unsure = !(xsimd::abs(h) > 1e-3f * r2);
  const Batch s = xsimd::sqrt(xsimd::max(h, Batch(0.0f)));
  r.t0 = xsimd::max(-b - s, Batch(0.0f));
  r.t1 = xsimd::min(-b + s, tmax);
  r.hit = (h >= 0.0f) & (r.t0 <= r.t1);
}

// ray_cone_interval: the pieces of f(t) = a t^2 + 2 b t + c >= 0 on the nappe's half-space,
// with a first-order bound on each float quantity's error; lanes whose answer that error
// could change are unsure.
void LightVolumeLanes::cone(const Batch& ox, const Batch& oy, const Batch& oz, const Batch& dx,
                            const Batch& dy, const Batch& dz, const Batch& tmax, Result& r) const {
  const Batch vx = ox - centre_.x, vy = oy - centre_.y, vz = oz - centre_.z;
  const Batch da = dx * axis_.x + dy * axis_.y + dz * axis_.z;
  const Batch va = vx * axis_.x + vy * axis_.y + vz * axis_.z;
  const Batch dv = dx * vx + dy * vy + dz * vz;
  const Batch vv = vx * vx + vy * vy + vz * vz;
  const Batch a = da * da - cos2_;
  const Batch b = da * va - cos2_ * dv;
  const Batch c = va * va - cos2_ * vv;
  const Batch disc = b * b - a * c;
  const Batch abs_a = xsimd::abs(a), abs_b = xsimd::abs(b), abs_c = xsimd::abs(c);
  const Batch len = xsimd::sqrt(vv);
  const Batch err_a(kEps);
  const Batch err_b = kEps * (xsimd::abs(da * va) + cos2_ * xsimd::abs(dv));
  const Batch err_c = kEps * (va * va + cos2_ * vv);
  const Batch err_disc =
      2.0f * abs_b * err_b + abs_a * err_c + abs_c * err_a + kEps * (b * b + abs_a * abs_c);
  // Rays nearly parallel to a generator (a ~ 0) degenerate the quadratic: one root runs off
  // to infinity and which side of it the ray lies on rests on a's last bits, which differ
  // with the compiler's choices (-O2 and -O3 disagreed on a grazing test ray). Unsure.
  Mask unsure = (!(xsimd::abs(disc) > err_disc)) | (!(xsimd::abs(da) > 1e-6f)) | (!(abs_a > 1e-4f));

  // Roots (no cancellation in b + sign(b) sqrt(disc)), sorted; q != 0 where disc > 0.
  const Batch root = xsimd::sqrt(xsimd::max(disc, Batch(0.0f)));
  const Batch q = -(b + xsimd::select(b < 0.0f, -root, root));
  const Batch safe_q = xsimd::select(q == 0.0f, Batch(1.0f), q);
  const Batch safe_a = xsimd::select(a == 0.0f, Batch(1.0f), a);
  const Batch ra = q / safe_a, rb = c / safe_q;
  const Batch err_q = err_b + err_disc / (2.0f * root + 1e-30f);
  const Batch abs_q = xsimd::abs(safe_q);
  const Batch err_ra = (err_q + xsimd::abs(ra) * err_a) / xsimd::abs(safe_a);
  const Batch err_rb = (err_c + xsimd::abs(rb) * err_q) / abs_q;
  const Mask ordered = ra <= rb;
  const Batch r0 = xsimd::select(ordered, ra, rb), r1 = xsimd::select(ordered, rb, ra);
  const Batch err_r0 = xsimd::select(ordered, err_ra, err_rb),
              err_r1 = xsimd::select(ordered, err_rb, err_ra);

  // Half-space v.axis >= 0: t >= h (da > 0) or t <= h (da < 0).
  const Batch h = -va / xsimd::select(da == 0.0f, Batch(1.0f), da);
  const Batch err_h = (kEps * len + xsimd::abs(h) * kEps) / xsimd::abs(da);
  const Batch h0 = xsimd::select(da > 0.0f, h, Batch(-kInf));
  const Batch h1 = xsimd::select(da > 0.0f, Batch(kInf), h);

  const Mask real = disc > 0.0f, opens_up = a > 0.0f;
  // A root that matters (inside the ray's span) must be accurate, and must not be so near
  // the half-space's edge (rays past the apex) that the piece choice could flip.
  const Batch slack = kTol * (1.0f + len);
  auto shaky = [&](const Batch& t, const Batch& err_r) {
    const Mask in_play = (t > -slack - err_r) & (t < tmax + slack + err_r);
    const Mask inaccurate = !(err_r <= slack + kTol * xsimd::abs(t));
    const Mask near_edge = xsimd::abs(t - h) <= err_r + err_h + slack;
    return real & ((inaccurate & in_play) | near_edge);
  };
  unsure = unsure | shaky(r0, err_r0) | shaky(r1, err_r1);

  // The pieces of f >= 0: (-inf, r0] and [r1, inf) when a > 0, [r0, r1] when a < 0; the
  // whole line (a > 0) or nothing (a < 0) without real roots.
  const Batch p0_lo = xsimd::select(opens_up, Batch(-kInf), r0);
  const Batch p0_hi = xsimd::select(real, xsimd::select(opens_up, r0, r1), Batch(kInf));
  const Mask p0_exists = real | opens_up;
  const Batch p1_lo = r1;
  const Mask p1_exists = real & opens_up;
  const Batch tmin(0.0f);
  const Batch lo0 = xsimd::max(xsimd::max(p0_lo, h0), tmin), hi0 = xsimd::min(xsimd::min(p0_hi, h1), tmax);
  const Batch lo1 = xsimd::max(xsimd::max(p1_lo, h0), tmin), hi1 = xsimd::min(h1, tmax);
  const Mask s0 = p0_exists & (lo0 <= hi0), s1 = p1_exists & (lo1 <= hi1);
  // Both survive only at the apex: their hull, as the scalar test.
  r.t0 = xsimd::select(s0, lo0, lo1);
  r.t1 = xsimd::select(s1, hi1, hi0);
  r.hit = s0 | s1;  // rays along the nappe's plane (da ~ 0) are unsure
  r.unsure = unsure;
}

// ray_box_light_interval, the same float arithmetic lane-parallel.
void LightVolumeLanes::box(const Batch& ox, const Batch& oy, const Batch& oz, const Batch& dx,
                           const Batch& dy, const Batch& dz, const Batch& tmax, Result& r) const {
  const Batch rx = ox - centre_.x, ry = oy - centre_.y, rz = oz - centre_.z;
  Batch t0(0.0f), t1 = tmax;
  Mask miss(false);
  for (int i = 0; i < 3; ++i) {
    const Vec3 axis = box_axes_[i];
    const Batch o = rx * axis.x + ry * axis.y + rz * axis.z;
    const Batch d = dx * axis.x + dy * axis.y + dz * axis.z;
    const Mask parallel = d == 0.0f;
    miss = miss | (parallel & ((o < box_lo_[i]) | (o > box_hi_[i])));
    const Batch inv_d = xsimd::select(parallel, Batch(1.0f), d);
    const Batch tn = (box_lo_[i] - o) / inv_d, tf = (box_hi_[i] - o) / inv_d;
    t0 = xsimd::select(parallel, t0, xsimd::max(t0, xsimd::min(tn, tf)));
    t1 = xsimd::select(parallel, t1, xsimd::min(t1, xsimd::max(tn, tf)));
  }
  r.t0 = t0;
  r.t1 = t1;
  r.hit = (t0 <= t1) & (!miss);
}

}  // namespace caligo
