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

namespace {

// f(t) = a t^2 + 2 b t + c >= 0 inside the double cone, v = origin - apex + t dir, with a
// first-order bound on each float quantity's error.
struct ConeQuadratic {
  Batch a, b, c, disc, err_a, err_b, err_c, err_disc;
  Batch da, va, len;  // dir . axis, (origin - apex) . axis, |origin - apex|
};

ConeQuadratic cone_quadratic(const Rays& rays, Vec3 apex, Vec3 axis, float cos2) {
  const Batch &dx = rays.dx, &dy = rays.dy, &dz = rays.dz;
  const Batch vx = rays.ox - apex.x, vy = rays.oy - apex.y, vz = rays.oz - apex.z;
  ConeQuadratic q;
  q.da = dx * axis.x + dy * axis.y + dz * axis.z;
  q.va = vx * axis.x + vy * axis.y + vz * axis.z;
  const Batch dv = dx * vx + dy * vy + dz * vz;
  const Batch vv = vx * vx + vy * vy + vz * vz;
  q.a = q.da * q.da - cos2;
  q.b = q.da * q.va - cos2 * dv;
  q.c = q.va * q.va - cos2 * vv;
  q.disc = q.b * q.b - q.a * q.c;
  q.len = xsimd::sqrt(vv);
  const Batch abs_a = xsimd::abs(q.a), abs_b = xsimd::abs(q.b), abs_c = xsimd::abs(q.c);
  q.err_a = Batch(kEps);
  q.err_b = kEps * (xsimd::abs(q.da * q.va) + cos2 * xsimd::abs(dv));
  q.err_c = kEps * (q.va * q.va + cos2 * vv);
  q.err_disc = 2.0f * abs_b * q.err_b + abs_a * q.err_c + abs_c * q.err_a + kEps * (q.b * q.b + abs_a * abs_c);
  return q;
}

// The quadratic's roots r0 <= r1 (no cancellation in b + sign(b) sqrt(disc); q != 0 where
// disc > 0) and their error bounds.
struct SortedRoots {
  Batch r0, r1, err_r0, err_r1;
};

SortedRoots sorted_roots(const ConeQuadratic& f) {
  const Batch root = xsimd::sqrt(xsimd::max(f.disc, Batch(0.0f)));
  const Batch q = -(f.b + xsimd::select(f.b < 0.0f, -root, root));
  const Batch safe_q = xsimd::select(q == 0.0f, Batch(1.0f), q);
  const Batch safe_a = xsimd::select(f.a == 0.0f, Batch(1.0f), f.a);
  const Batch ra = q / safe_a, rb = f.c / safe_q;
  const Batch err_q = f.err_b + f.err_disc / (2.0f * root + 1e-30f);
  const Batch err_ra = (err_q + xsimd::abs(ra) * f.err_a) / xsimd::abs(safe_a);
  const Batch err_rb = (f.err_c + xsimd::abs(rb) * err_q) / xsimd::abs(safe_q);
  const Mask ordered = ra <= rb;
  return {xsimd::select(ordered, ra, rb), xsimd::select(ordered, rb, ra), xsimd::select(ordered, err_ra, err_rb),
          xsimd::select(ordered, err_rb, err_ra)};
}

}  // namespace

// The pieces of f >= 0 on the nappe's half-space; lanes whose answer the float error bounds
// could change are unsure.
Ranges ray_cone(const Rays& rays, Vec3 apex, Vec3 axis, float cos2) {
  const ConeQuadratic f = cone_quadratic(rays, apex, axis, cos2);
  const SortedRoots roots = sorted_roots(f);
  // Rays nearly parallel to a generator (a ~ 0) degenerate the quadratic: one root runs off
  // to infinity and which side of it the ray lies on rests on a's last bits, which differ
  // with the compiler's choices (-O2 and -O3 disagreed on a grazing test ray). Unsure.
  Mask unsure = (!(xsimd::abs(f.disc) > f.err_disc)) | (!(xsimd::abs(f.da) > 1e-6f)) | (!(xsimd::abs(f.a) > 1e-4f));
  // Half-space v.axis >= 0: t >= h (da > 0) or t <= h (da < 0).
  const Batch h = -f.va / xsimd::select(f.da == 0.0f, Batch(1.0f), f.da);
  const Batch err_h = (kEps * f.len + xsimd::abs(h) * kEps) / xsimd::abs(f.da);
  const Batch h0 = xsimd::select(f.da > 0.0f, h, Batch(-kInf));
  const Batch h1 = xsimd::select(f.da > 0.0f, Batch(kInf), h);
  const Mask real = f.disc > 0.0f, opens_up = f.a > 0.0f;
  // A root that matters (inside the ray's span) must be accurate, and must not be so near
  // the half-space's edge (rays past the apex) that the piece choice could flip.
  const Batch slack = kTol * (1.0f + f.len);
  auto shaky = [&](const Batch& t, const Batch& err_r) {
    const Mask in_play = (t > -slack - err_r) & (t < rays.tmax + slack + err_r);
    const Mask inaccurate = !(err_r <= slack + kTol * xsimd::abs(t));
    const Mask near_edge = xsimd::abs(t - h) <= err_r + err_h + slack;
    return real & ((inaccurate & in_play) | near_edge);
  };
  unsure = unsure | shaky(roots.r0, roots.err_r0) | shaky(roots.r1, roots.err_r1);
  // The pieces of f >= 0: (-inf, r0] and [r1, inf) when a > 0, [r0, r1] when a < 0; the
  // whole line (a > 0) or nothing (a < 0) without real roots.
  const Batch p0_lo = xsimd::select(opens_up, Batch(-kInf), roots.r0);
  const Batch p0_hi = xsimd::select(real, xsimd::select(opens_up, roots.r0, roots.r1), Batch(kInf));
  const Mask p0_exists = real | opens_up, p1_exists = real & opens_up;
  const Batch tmin(0.0f);
  const Batch lo0 = xsimd::max(xsimd::max(p0_lo, h0), tmin), hi0 = xsimd::min(xsimd::min(p0_hi, h1), rays.tmax);
  const Batch lo1 = xsimd::max(xsimd::max(roots.r1, h0), tmin), hi1 = xsimd::min(h1, rays.tmax);
  const Mask s0 = p0_exists & (lo0 <= hi0), s1 = p1_exists & (lo1 <= hi1);
  // Both survive only at the apex: their hull, as the scalar test. Rays along the nappe's
  // plane (da ~ 0) are unsure.
  return {xsimd::select(s0, lo0, lo1), xsimd::select(s1, hi1, hi0), s0 | s1, unsure};
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
