#include "core/ray_solids_lanes.h"

#include <limits>

namespace caligo::lanes {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
// Relative error bound of one float operation chain below (a few ulps, generously).
constexpr float kEps = 2e-6f;
// How far (relative to the magnitudes involved) an interval end may sit from the scalar
// double answer before a lane is handed to the scalar test.
constexpr float kTol = 1e-4f;

}  // namespace

// Relative to the closest point on the line, as the scalar sphere_roots.
Ranges ray_ball(const Rays& rays, Vec3 centre, float radius) {
  const Batch cx = rays.ox - centre.x, cy = rays.oy - centre.y, cz = rays.oz - centre.z;
  const Batch b = cx * rays.dx + cy * rays.dy + cz * rays.dz;
  const Batch qx = cx - rays.dx * b, qy = cy - rays.dy * b, qz = cz - rays.dz * b;
  const float r2 = radius * radius;
  const Batch h = r2 - (qx * qx + qy * qy + qz * qz);
  Ranges r;
  // Near-tangent lines: the chord's half length sqrt(h) is ill-conditioned in float.
  r.unsure = !(xsimd::abs(h) > 1e-3f * r2);
  const Batch s = xsimd::sqrt(xsimd::max(h, Batch(0.0f)));
  r.t0 = xsimd::max(-b - s, Batch(0.0f));
  r.t1 = xsimd::min(-b + s, rays.tmax);
  r.hit = (h >= 0.0f) & (r.t0 <= r.t1);
  return r;
}

// The pieces of f(t) = a t^2 + 2 b t + c >= 0 on the nappe's half-space, with a first-order
// bound on each float quantity's error; lanes whose answer that error could change are unsure.
Ranges ray_cone(const Rays& rays, Vec3 apex, Vec3 axis, float cos2) {
  const Batch &dx = rays.dx, &dy = rays.dy, &dz = rays.dz, &tmax = rays.tmax;
  const Batch vx = rays.ox - apex.x, vy = rays.oy - apex.y, vz = rays.oz - apex.z;
  const Batch da = dx * axis.x + dy * axis.y + dz * axis.z;
  const Batch va = vx * axis.x + vy * axis.y + vz * axis.z;
  const Batch dv = dx * vx + dy * vy + dz * vz;
  const Batch vv = vx * vx + vy * vy + vz * vz;
  const Batch a = da * da - cos2;
  const Batch b = da * va - cos2 * dv;
  const Batch c = va * va - cos2 * vv;
  const Batch disc = b * b - a * c;
  const Batch abs_a = xsimd::abs(a), abs_b = xsimd::abs(b), abs_c = xsimd::abs(c);
  const Batch len = xsimd::sqrt(vv);
  const Batch err_a(kEps);
  const Batch err_b = kEps * (xsimd::abs(da * va) + cos2 * xsimd::abs(dv));
  const Batch err_c = kEps * (va * va + cos2 * vv);
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
  Ranges r;
  r.t0 = xsimd::select(s0, lo0, lo1);
  r.t1 = xsimd::select(s1, hi1, hi0);
  r.hit = s0 | s1;  // rays along the nappe's plane (da ~ 0) are unsure
  r.unsure = unsure;
  return r;
}

// The scalar slab test's float arithmetic, lane by lane (zero components: all or nothing).
Ranges ray_oriented_box(const Rays& rays, const OrientedBox& box) {
  const Batch rx = rays.ox - box.origin.x, ry = rays.oy - box.origin.y, rz = rays.oz - box.origin.z;
  Batch t0(0.0f), t1 = rays.tmax;
  Mask miss(false);
  for (int i = 0; i < 3; ++i) {
    const Vec3 axis = box.axes[size_t(i)];
    const Batch o = rx * axis.x + ry * axis.y + rz * axis.z;
    const Batch d = rays.dx * axis.x + rays.dy * axis.y + rays.dz * axis.z;
    const Mask parallel = d == 0.0f;
    miss = miss | (parallel & ((o < box.lo[i]) | (o > box.hi[i])));
    const Batch inv = Batch(1.0f) / xsimd::select(parallel, Batch(1.0f), d);
    const Batch tn = (box.lo[i] - o) * inv, tf = (box.hi[i] - o) * inv;
    t0 = xsimd::select(parallel, t0, xsimd::max(t0, xsimd::min(tn, tf)));
    t1 = xsimd::select(parallel, t1, xsimd::min(t1, xsimd::max(tn, tf)));
  }
  return {t0, t1, (t0 <= t1) & (!miss), Mask(false)};
}

Ranges overlap(const Ranges& a, const Ranges& b) {
  Ranges r;
  r.t0 = xsimd::max(a.t0, b.t0);
  r.t1 = xsimd::min(a.t1, b.t1);
  r.hit = a.hit & b.hit & (r.t0 <= r.t1);
  r.unsure = a.unsure | b.unsure;
  return r;
}

}  // namespace caligo::lanes
