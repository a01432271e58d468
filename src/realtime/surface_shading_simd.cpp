// 8-wide surface shading (xsimd, AVX2): the point, spot, box and directional light models
// of lights/light_profile.cpp for lights without a gobo image or IES profile, written once
// more over batches. Everything else (gobo/IES lights, media transmittance, cube-map
// normal offsets) calls the scalar functions lane by lane, so the two paths share one
// definition of the physics; surface_shading_test.cpp compares them.
#include <xsimd/xsimd.hpp>

#include <cmath>

#include "realtime/shadow_map_simd.h"
#include "realtime/surface_shading_internal.h"

namespace caligo::shading {
namespace {

using B = xsimd::batch<float>;
using Mask = xsimd::batch_bool<float>;
constexpr size_t kLanes = B::size;

struct V3 {
  B x, y, z;
};
inline B dot(const V3& a, Vec3 b) { return a.x * B(b.x) + a.y * B(b.y) + a.z * B(b.z); }
inline B dot(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 minus(Vec3 a, const V3& b) { return {B(a.x) - b.x, B(a.y) - b.y, B(a.z) - b.z}; }
inline V3 minus(const V3& a, Vec3 b) { return {a.x - B(b.x), a.y - B(b.y), a.z - B(b.z)}; }
inline V3 madd(const V3& a, const V3& d, B t) { return {a.x + d.x * t, a.y + d.y * t, a.z + d.z * t}; }
inline Vec3 lane(const V3& v, size_t i) { return {v.x.get(i), v.y.get(i), v.z.get(i)}; }

// lights/light_profile.cpp's range_window and math.h's smoothstep, over batches.
B range_window(B distance, float range) {
  if (!(range < kInfinity)) return B(1.0f);
  const B t = distance / B(range);
  const B x = (t * t) * (t * t);
  return xsimd::select(distance < B(range), (B(1.0f) - x) * (B(1.0f) - x), B(0.0f));
}
B smoothstep(float e0, float e1, B x) {
  if (e0 == e1) return xsimd::select(x < B(e0), B(0.0f), B(1.0f));
  const B t = xsimd::clip((x - B(e0)) / B(e1 - e0), B(0.0f), B(1.0f));
  return t * t * (B(3.0f) - B(2.0f) * t);
}

struct Arrival {
  B r, g, b;  // radiance (already / d^2) or irradiance
  V3 wi;      // towards the light
  B distance;
  Mask mask;  // where the light arrives
};

struct ArrivalAt {
  const V3& p;
  float far;

  Arrival point_like(Vec3 position, RGB intensity, float range) const {
    const V3 d = minus(position, p);
    const B dist2 = dot(d, d);
    const B dist = xsimd::sqrt(dist2);
    const B inv = B(1.0f) / dist;
    const V3 wi{d.x * inv, d.y * inv, d.z * inv};
    const B scale = range_window(dist, range) / dist2;
    return {B(intensity.r) * scale,
            B(intensity.g) * scale,
            B(intensity.b) * scale,
            wi,
            dist,
            (dist2 > B(0.0f)) & (scale > B(0.0f))};
  }
  Arrival operator()(const PointLight& l) const { return point_like(l.position, l.intensity, l.range); }
  Arrival operator()(const SpotLight& l) const {
    Arrival a = point_like(l.position, l.intensity, l.range);
    const B cone = smoothstep(l.cos_outer, l.cos_inner, B(0.0f) - dot(a.wi, l.direction));
    a.r *= cone, a.g *= cone, a.b *= cone;
    a.mask = a.mask & (cone > B(0.0f));
    return a;
  }
  Arrival operator()(const BoxLight& l) const {
    const V3 local = minus(p, l.position);
    const B along = dot(local, l.direction);
    const Vec3 right = cross(l.direction, l.up);
    const B x = dot(local, right), y = dot(local, l.up);
    const Mask inside = (along >= B(0.0f)) & (along <= B(l.range)) & (xsimd::abs(x) <= B(l.half_width)) &
                        (xsimd::abs(y) <= B(l.half_height));
    const V3 wi{B(-l.direction.x), B(-l.direction.y), B(-l.direction.z)};
    return {B(l.irradiance.r), B(l.irradiance.g), B(l.irradiance.b), wi, along, inside};
  }
  Arrival operator()(const DirectionalLight& l) const {
    const V3 wi{B(-l.direction.x), B(-l.direction.y), B(-l.direction.z)};
    return {B(l.irradiance.r), B(l.irradiance.g), B(l.irradiance.b), wi, B(far), Mask(true)};
  }
  // Never called: simple() is false for these (and tile culling drops them).
  Arrival operator()(const SphereLight&) const { return none(); }
  Arrival operator()(const QuadLight&) const { return none(); }
  Arrival operator()(const TriangleLight&) const { return none(); }
  Arrival operator()(const EnvironmentLight&) const { return none(); }
  static Arrival none() {
    return {B(0.0f), B(0.0f), B(0.0f), {B(0.0f), B(0.0f), B(0.0f)}, B(0.0f), Mask(false)};
  }
};

// Lights whose emission the batch code models completely.
struct Simple {
  bool operator()(const PointLight& l) const { return !l.ies.profile; }
  bool operator()(const SpotLight& l) const { return !l.ies.profile && !l.gobo.image; }
  bool operator()(const BoxLight& l) const { return !l.gobo.image; }
  bool operator()(const DirectionalLight&) const { return true; }
  bool operator()(const SphereLight&) const { return false; }
  bool operator()(const QuadLight&) const { return false; }
  bool operator()(const TriangleLight&) const { return false; }
  bool operator()(const EnvironmentLight&) const { return false; }
};

// Shadow visibility at p offset by one texel along n (the scalar path's normal offset).
B shadowed_visibility(const ShadowMap& map, const V3& p, const V3& n) {
  const int face = map.faces.size() == 1 ? 0 : shadow_detail::common_cube_face(map, p.x, p.y, p.z);
  B texel;
  if (face >= 0) {
    const View& v = map.faces[size_t(face)];
    const float h = float(v.resolution.y);
    texel = v.projection == Projection::perspective
                ? xsimd::abs(dot(minus(p, v.eye), v.forward)) * B(2.0f * v.tan_half_fov_y / h)
                : B(2.0f * v.half_height / h);
  } else {
    alignas(32) float t[kLanes];
    for (size_t i = 0; i < kLanes; ++i) t[i] = map.texel_size(lane(p, i));
    texel = B::load_aligned(t);
  }
  const V3 q = madd(p, n, texel);
  return shadow_visibility(map, q.x, q.y, q.z);
}

// Per-lane scalar transmittance between a and b (media are rare and irregular).
void lane_transmittance(const VolumeScene& volumes, const V3& a, const V3& b, Mask m, B& r, B& g, B& bl) {
  alignas(32) float tr[3][kLanes];
  for (size_t i = 0; i < kLanes; ++i) {
    const RGB t = m.get(i) ? transmittance(volumes, lane(a, i), lane(b, i)) : RGB(0.0f);
    tr[0][i] = t.r, tr[1][i] = t.g, tr[2][i] = t.b;
  }
  r = B::load_aligned(tr[0]), g = B::load_aligned(tr[1]), bl = B::load_aligned(tr[2]);
}

struct Group {
  V3 p, eye, n;
  Mask valid;
  B fr, fg, fb;  // albedo / pi (0 for non-diffuse materials)
  Mask diffuse;
  B r, g, b;  // radiance so far
};

void add_simple_light(const ShadeContext& c, const FrameLight& fl, Group& q) {
  const Arrival a = std::visit(ArrivalAt{q.p, c.far}, fl.light);
  const B cos_theta = dot(q.n, a.wi);
  Mask m = q.valid & q.diffuse & a.mask & (cos_theta > B(0.0f));
  if (!xsimd::any(m)) return;
  B weight = xsimd::select(m, cos_theta, B(0.0f));
  if (fl.shadow) weight *= shadowed_visibility(*fl.shadow, q.p, q.n);
  B tr_r(1.0f), tr_g(1.0f), tr_b(1.0f);
  if (!c.scene.volumes().empty())
    lane_transmittance(c.scene.volumes(), q.p, madd(q.p, a.wi, a.distance), m, tr_r, tr_g, tr_b);
  // Masked lanes may hold inf or NaN (a point at the light): select, never multiply by 0.
  q.r += xsimd::select(m, q.fr * a.r * weight * tr_r, B(0.0f));
  q.g += xsimd::select(m, q.fg * a.g * weight * tr_g, B(0.0f));
  q.b += xsimd::select(m, q.fb * a.b * weight * tr_b, B(0.0f));
}

void add_scalar_light(const ShadeContext& c, const FrameLight& fl, Group& q) {
  alignas(32) float out[3][kLanes];
  for (size_t i = 0; i < kLanes; ++i) {
    RGB l;
    if (q.valid.get(i) && q.diffuse.get(i))
      l = light_term(c, fl, lane(q.p, i), lane(q.n, i), RGB(q.fr.get(i), q.fg.get(i), q.fb.get(i)));
    out[0][i] = l.r, out[1][i] = l.g, out[2][i] = l.b;
  }
  q.r += B::load_aligned(out[0]), q.g += B::load_aligned(out[1]), q.b += B::load_aligned(out[2]);
}

// Positions, normals, materials and emission of pixels x .. x + 7 of row y.
Group load_group(const ShadeContext& c, int x, int y, B depth) {
  alignas(32) static constexpr float kLaneCentres[kLanes] = {0.5f, 1.5f, 2.5f, 3.5f, 4.5f, 5.5f, 6.5f, 7.5f};
  const View& v = c.camera;
  const size_t pixel = size_t(y) * size_t(c.g.depth.width) + size_t(x);
  Group q;
  q.valid = depth < B(kSkyDepth);
  depth = xsimd::select(q.valid, depth, B(1.0f));
  const B px = B(float(x)) + B::load_aligned(kLaneCentres);
  const B ndc_x = B(2.0f) * px / B(float(v.resolution.x)) - B(1.0f);
  const float ndc_y = 1.0f - 2.0f * (float(y) + 0.5f) / float(v.resolution.y);
  if (v.projection == Projection::perspective) {
    // The unnormalised ray direction has unit forward component, so p = eye + d * depth.
    const B a = ndc_x * B(v.tan_half_fov_y * v.aspect);
    const float b = ndc_y * v.tan_half_fov_y;
    const V3 d{B(v.forward.x + v.up.x * b) + B(v.right.x) * a, B(v.forward.y + v.up.y * b) + B(v.right.y) * a,
               B(v.forward.z + v.up.z * b) + B(v.right.z) * a};
    q.eye = {B(v.eye.x), B(v.eye.y), B(v.eye.z)};
    q.p = madd(q.eye, d, depth);
  } else {
    const B a = ndc_x * B(v.half_width);
    const float b = ndc_y * v.half_height;
    q.eye = {B(v.eye.x + v.up.x * b) + B(v.right.x) * a, B(v.eye.y + v.up.y * b) + B(v.right.y) * a,
             B(v.eye.z + v.up.z * b) + B(v.right.z) * a};
    q.p = madd(q.eye, {B(v.forward.x), B(v.forward.y), B(v.forward.z)}, depth);
  }
  q.n = {B::load_unaligned(c.g.nx.data.data() + pixel), B::load_unaligned(c.g.ny.data.data() + pixel),
         B::load_unaligned(c.g.nz.data.data() + pixel)};
  alignas(32) float f[3][kLanes], e[3][kLanes], diffuse[kLanes];
  for (size_t i = 0; i < kLanes; ++i) {
    const int32_t m = c.g.material[pixel + i];
    RGB fi, ei;
    diffuse[i] = 0.0f;
    if (m >= 0) {
      const Material& mat = c.scene.materials()[size_t(m)];
      if (!mat.emission.is_black() && (c.g.front[pixel + i] || mat.two_sided_emission)) ei = mat.emission;
      if (const auto* d = std::get_if<DiffuseBsdf>(&mat.bsdf))
        fi = d->reflectance * kInvPi, diffuse[i] = 1.0f;
    }
    f[0][i] = fi.r, f[1][i] = fi.g, f[2][i] = fi.b;
    e[0][i] = ei.r, e[1][i] = ei.g, e[2][i] = ei.b;
  }
  q.fr = B::load_aligned(f[0]), q.fg = B::load_aligned(f[1]), q.fb = B::load_aligned(f[2]);
  q.r = B::load_aligned(e[0]), q.g = B::load_aligned(e[1]), q.b = B::load_aligned(e[2]);
  q.diffuse = B::load_aligned(diffuse) > B(0.0f);
  return q;
}

}  // namespace

int shade_row_simd(const ShadeContext& c, int y, int x0, int x1, std::span<const int> active,
                   ColorPlanes& out) {
  int x = x0;
  for (; x + int(kLanes) <= x1; x += int(kLanes)) {
    const B depth = B::load_unaligned(c.g.depth.row(y) + x);
    if (!xsimd::any(depth < B(kSkyDepth))) continue;
    Group q = load_group(c, x, y, depth);
    if (xsimd::any(q.valid & q.diffuse))
      for (int i : active) {
        const FrameLight& fl = c.lights[size_t(i)];
        if (std::visit(Simple{}, fl.light))
          add_simple_light(c, fl, q);
        else
          add_scalar_light(c, fl, q);
      }
    if (!c.scene.volumes().empty()) {
      B tr_r, tr_g, tr_b;
      lane_transmittance(c.scene.volumes(), q.eye, q.p, q.valid, tr_r, tr_g, tr_b);
      q.r *= tr_r, q.g *= tr_g, q.b *= tr_b;
    }
    xsimd::select(q.valid, q.r, B(0.0f)).store_unaligned(out.r.row(y) + x);
    xsimd::select(q.valid, q.g, B(0.0f)).store_unaligned(out.g.row(y) + x);
    xsimd::select(q.valid, q.b, B(0.0f)).store_unaligned(out.b.row(y) + x);
  }
  return x;
}

}  // namespace caligo::shading
