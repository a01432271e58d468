// 8-wide surface shading (xsimd, AVX2): the point, spot, box and directional light models
// through light_lanes.h (the accumulation march's own), media transmittance through
// media_simd.h, shadows through
// shadow_map_simd.h. Everything that does
// not change over a frame (material tables, gobo rotations, light frames, the media in
// object space) is derived once in prepare_simd. surface_shading_test.cpp compares the
// result with the scalar reference path.
#include <immintrin.h>

#include <cmath>
#include <optional>
#include <vector>

#include <xsimd/xsimd.hpp>

#include "realtime/light_lanes.h"
#include "realtime/media_simd.h"
#include "realtime/shadow_map_simd.h"
#include "realtime/surface_shading_internal.h"

namespace caligo::shading {
namespace {

using B = xsimd::batch<float>;
using I = xsimd::batch<int32_t>;
using Mask = xsimd::batch_bool<float>;
constexpr size_t kLanes = B::size;

struct V3 {
  B x, y, z;
};
inline B dot(const V3& a, Vec3 b) { return a.x * B(b.x) + a.y * B(b.y) + a.z * B(b.z); }
inline B dot(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 minus(const V3& a, Vec3 b) { return {a.x - B(b.x), a.y - B(b.y), a.z - B(b.z)}; }
inline V3 madd(const V3& a, const V3& d, B t) { return {a.x + d.x * t, a.y + d.y * t, a.z + d.z * t}; }
inline Vec3 lane(const V3& v, size_t i) { return {v.x.get(i), v.y.get(i), v.z.get(i)}; }
inline B gather(const float* base, const I& index) { return B(_mm256_i32gather_ps(base, index, 4)); }

struct Arrival {
  B r, g, b;  // radiance (already / d^2) or irradiance
  V3 wi;      // towards the light
  B distance;
  Mask mask;  // where the light arrives
};

// The light's 8-lane arrival (light_lanes.h); parallel lights' light ends `far` away.
Arrival arrival_at(const LightLanes& light, const V3& p, float far) {
  const LightLanes::Arrival a = light.at(p.x, p.y, p.z);
  return {a.r, a.g, a.b, {a.wx, a.wy, a.wz}, xsimd::min(a.distance, B(far)), a.mask};
}

// Shadow visibility at p offset by one texel along n (the scalar path's normal offset).
B shadowed_visibility(const ShadowMap& map, const V3& p, const V3& n) {
  const int face = shadow_detail::common_face(map, p.x, p.y, p.z);
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
  return surface_shadow_visibility(map, q.x, q.y, q.z);
}

struct Group {
  V3 p, eye, n;
  Mask valid;
  B fr, fg, fb;  // albedo / pi (0 for non-diffuse materials)
  Mask diffuse;
  B r, g, b;  // radiance so far
};

// Surface points and camera-ray origins of pixels x .. x + 7 of row y at linear depth.
// Sky lanes get depth 1 (finite arithmetic); callers mask them with `valid`.
void reconstruct(const View& v, int x, int y, B depth, V3& p, V3& eye) {
  alignas(32) static constexpr float kLaneCentres[kLanes] = {0.5f, 1.5f, 2.5f, 3.5f, 4.5f, 5.5f, 6.5f, 7.5f};
  const B px = B(float(x)) + B::load_aligned(kLaneCentres);
  const B ndc_x = B(2.0f) * px / B(float(v.resolution.x)) - B(1.0f);
  const float ndc_y = 1.0f - 2.0f * (float(y) + 0.5f) / float(v.resolution.y);
  if (v.projection == Projection::perspective) {
    // The unnormalised ray direction has unit forward component, so p = eye + d * depth.
    const B a = ndc_x * B(v.tan_half_fov_y * v.aspect);
    const float b = ndc_y * v.tan_half_fov_y;
    const V3 d{B(v.forward.x + v.up.x * b) + B(v.right.x) * a, B(v.forward.y + v.up.y * b) + B(v.right.y) * a,
               B(v.forward.z + v.up.z * b) + B(v.right.z) * a};
    eye = {B(v.eye.x), B(v.eye.y), B(v.eye.z)};
    p = madd(eye, d, depth);
  } else {
    const B a = ndc_x * B(v.half_width);
    const float b = ndc_y * v.half_height;
    eye = {B(v.eye.x + v.up.x * b) + B(v.right.x) * a, B(v.eye.y + v.up.y * b) + B(v.right.y) * a,
           B(v.eye.z + v.up.z * b) + B(v.right.z) * a};
    p = madd(eye, {B(v.forward.x), B(v.forward.y), B(v.forward.z)}, depth);
  }
}

// A tile's rows are 7.7 KB apart at 1080p, one or two cache lines per buffer each: too
// scattered for the hardware prefetchers, and the shading loop stalled on its loads. While
// the bounds pass walks a row, fetch the next row's depth and this row's normals, materials
// and face flags, which the shading pass reads right after.
void prefetch_row(const GBuffer& g, int y, int x0, int x1) {
  const size_t w = size_t(g.depth.width);
  const size_t row = size_t(y) * w;
  const size_t next = y + 1 < g.depth.height ? row + w : row;
  for (int x = x0; x < x1; x += 16) {
    const size_t i = row + size_t(x);
    _mm_prefetch(reinterpret_cast<const char*>(g.depth.data.data() + next + size_t(x)), _MM_HINT_T0);
    _mm_prefetch(reinterpret_cast<const char*>(g.nx.data.data() + i), _MM_HINT_T0);
    _mm_prefetch(reinterpret_cast<const char*>(g.ny.data.data() + i), _MM_HINT_T0);
    _mm_prefetch(reinterpret_cast<const char*>(g.nz.data.data() + i), _MM_HINT_T0);
    _mm_prefetch(reinterpret_cast<const char*>(g.material.data() + i), _MM_HINT_T0);
    _mm_prefetch(reinterpret_cast<const char*>(g.front.data() + i), _MM_HINT_T0);
  }
}

}  // namespace

struct SimdFrame {
  explicit SimdFrame(const VolumeScene& volumes) : media(volumes) {}
  // Per material: albedo / pi (0 unless diffuse), emission, and 1 / 0 flags.
  std::vector<float> f[3], emission[3], diffuse, two_sided;
  std::vector<LightLanes> lights;  // per light of the context
  SegmentMediaBatch media;
};

void SimdFrameDeleter::operator()(SimdFrame* f) const { delete f; }

SimdFramePtr prepare_simd(const ShadeContext& c) {
  SimdFramePtr frame(new SimdFrame(c.scene.volumes()));
  for (const Material& m : c.scene.materials()) {
    const std::optional<RGB> d = shading::diffuse_f(m.bsdf);
    const RGB f = d.value_or(RGB(0.0f));
    for (int k = 0; k < 3; ++k) {
      frame->f[k].push_back(f[k]);
      frame->emission[k].push_back(m.emission[k]);
    }
    frame->diffuse.push_back(d ? 1.0f : 0.0f);
    frame->two_sided.push_back(m.two_sided_emission ? 1.0f : 0.0f);
  }
  for (const FrameLight& fl : c.lights) frame->lights.emplace_back(fl.light);
  return frame;
}

Bounds3 points_bounds_simd(const ShadeContext& c, int y0, int y1, int x0, int x1) {
  B lo_x(kInfinity), lo_y(kInfinity), lo_z(kInfinity);
  B hi_x(-kInfinity), hi_y(-kInfinity), hi_z(-kInfinity);
  for (int y = y0; y < y1; ++y) {
    prefetch_row(c.g, y, x0, x1);
    for (int x = x0; x < x1; x += int(kLanes)) {
      const B depth = B::load_unaligned(c.g.depth.row(y) + x);
      const Mask valid = depth < B(kSkyDepth);
      if (!xsimd::any(valid)) continue;
      V3 p, eye;
      reconstruct(c.camera, x, y, xsimd::select(valid, depth, B(1.0f)), p, eye);
      lo_x = xsimd::min(lo_x, xsimd::select(valid, p.x, B(kInfinity)));
      lo_y = xsimd::min(lo_y, xsimd::select(valid, p.y, B(kInfinity)));
      lo_z = xsimd::min(lo_z, xsimd::select(valid, p.z, B(kInfinity)));
      hi_x = xsimd::max(hi_x, xsimd::select(valid, p.x, B(-kInfinity)));
      hi_y = xsimd::max(hi_y, xsimd::select(valid, p.y, B(-kInfinity)));
      hi_z = xsimd::max(hi_z, xsimd::select(valid, p.z, B(-kInfinity)));
    }
  }
  alignas(32) float lanes[6][kLanes];
  lo_x.store_aligned(lanes[0]), lo_y.store_aligned(lanes[1]), lo_z.store_aligned(lanes[2]);
  hi_x.store_aligned(lanes[3]), hi_y.store_aligned(lanes[4]), hi_z.store_aligned(lanes[5]);
  Bounds3 b;
  for (size_t i = 0; i < kLanes; ++i) {
    b.lo = min(b.lo, Vec3(lanes[0][i], lanes[1][i], lanes[2][i]));
    b.hi = max(b.hi, Vec3(lanes[3][i], lanes[4][i], lanes[5][i]));
  }
  return b;
}

namespace {

// Positions, normals, materials and emission of pixels x .. x + 7 of row y.
Group load_group(const ShadeContext& c, const SimdFrame& f, int x, int y, B depth) {
  const size_t pixel = size_t(y) * size_t(c.g.depth.width) + size_t(x);
  Group q;
  q.valid = depth < B(kSkyDepth);
  reconstruct(c.camera, x, y, xsimd::select(q.valid, depth, B(1.0f)), q.p, q.eye);
  q.n = {B::load_unaligned(c.g.nx.data.data() + pixel), B::load_unaligned(c.g.ny.data.data() + pixel),
         B::load_unaligned(c.g.nz.data.data() + pixel)};
  const __m256i material = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(c.g.material.data() + pixel));
  const Mask has_material(_mm256_castsi256_ps(_mm256_cmpgt_epi32(material, _mm256_set1_epi32(-1))));
  const I m(_mm256_max_epi32(material, _mm256_setzero_si256()));
  // The front-face bytes widened to 32-bit lanes.
  const __m256i front =
      _mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(c.g.front.data() + pixel)));
  const Mask back(_mm256_castsi256_ps(_mm256_cmpeq_epi32(front, _mm256_setzero_si256())));
  const Mask lit = q.valid & has_material;
  q.diffuse = lit & (gather(f.diffuse.data(), m) > B(0.0f));
  const Mask glows = lit & ((!back) | (gather(f.two_sided.data(), m) > B(0.0f)));
  q.fr = xsimd::select(q.diffuse, gather(f.f[0].data(), m), B(0.0f));
  q.fg = xsimd::select(q.diffuse, gather(f.f[1].data(), m), B(0.0f));
  q.fb = xsimd::select(q.diffuse, gather(f.f[2].data(), m), B(0.0f));
  q.r = xsimd::select(glows, gather(f.emission[0].data(), m), B(0.0f));
  q.g = xsimd::select(glows, gather(f.emission[1].data(), m), B(0.0f));
  q.b = xsimd::select(glows, gather(f.emission[2].data(), m), B(0.0f));
  return q;
}

using Overlap = SegmentMediaBatch::Overlap;

// Where the light ends of one light's transmittance segments lie, for segments that start in
// the world box `from` (the surface points of a tile).
struct LightEnds {
  const Bounds3& from;
  float far;

  static Bounds3 point(Vec3 p) {
    Bounds3 b;
    b.extend(p);
    return b;
  }
  // `from` swept along v (to from + v).
  Bounds3 swept(Vec3 v) const {
    Bounds3 b = from;
    b.extend(Bounds3{from.lo + v, from.hi + v});
    return b;
  }
  Bounds3 operator()(const PointLight& l) const { return point(l.position); }
  Bounds3 operator()(const SpotLight& l) const { return point(l.position); }
  Bounds3 operator()(const BoxLight& l) const { return swept(-l.direction * l.range); }
  Bounds3 operator()(const DirectionalLight& l) const {
    const Vec3 v = -l.direction * far;
    return {from.lo + v, from.hi + v};
  }
};

void add_light(const ShadeContext& c, const SimdFrame& f, const FrameLight& fl, const LightLanes& prep,
               const Overlap* overlaps, Group& q) {
  const Arrival a = arrival_at(prep, q.p, c.far);
  const B cos_theta = dot(q.n, a.wi);
  Mask m = q.diffuse & a.mask & (cos_theta > B(0.0f));
  if (!xsimd::any(m)) return;
  B weight = xsimd::select(m, cos_theta, B(0.0f));
  if (const ShadowMap* map = fl.surface_map()) {
    weight *= shadowed_visibility(*map, q.p, q.n);
    m = m & (weight > B(0.0f));
    if (!xsimd::any(m)) return;
  }
  B tr_r(1.0f), tr_g(1.0f), tr_b(1.0f);
  if (!f.media.empty()) {
    const V3 l = madd(q.p, a.wi, a.distance);
    f.media.transmittance(q.p.x, q.p.y, q.p.z, l.x, l.y, l.z, m, overlaps, tr_r, tr_g, tr_b);
  }
  // Masked lanes may hold inf or NaN (a point at the light): select, never multiply by 0.
  q.r += xsimd::select(m, q.fr * a.r * weight * tr_r, B(0.0f));
  q.g += xsimd::select(m, q.fg * a.g * weight * tr_g, B(0.0f));
  q.b += xsimd::select(m, q.fb * a.b * weight * tr_b, B(0.0f));
}

}  // namespace

void shade_rect_simd(const ShadeContext& c, const SimdFrame& f, int y0, int y1, int x0, int x1,
                     std::span<const int> active, const Bounds3& bounds, ColorPlanes& out) {
  // How each primitive meets the camera segments (row 0) and each active light's (rows 1..).
  const size_t n = f.media.size();
  std::vector<Overlap> overlaps(n * (1 + active.size()));
  const bool perspective = c.camera.projection == Projection::perspective;
  if (n > 0) {
    if (perspective) f.media.classify(LightEnds::point(c.camera.eye), bounds, overlaps.data());
    for (size_t k = 0; k < active.size(); ++k)
      f.media.classify(bounds, std::visit(LightEnds{bounds, c.far}, c.lights[size_t(active[k])].light),
                       overlaps.data() + n * (1 + k));
  }
  // Orthographic camera rays start on a plane: test every primitive.
  const Overlap* camera_overlaps = perspective ? overlaps.data() : nullptr;
  // Groups are shaded in batches of up to kBatch, light by light: a light's shadow-map
  // gathers for neighbouring groups are then independent and their cache misses overlap
  // (group by group, each miss stalled the lights after it).
  constexpr size_t kBatch = 32;
  Group groups[kBatch];
  int gx[kBatch], gy[kBatch];
  size_t count = 0;
  const auto flush = [&] {
    for (size_t k = 0; k < active.size(); ++k) {
      const size_t i = size_t(active[k]);
      for (size_t j = 0; j < count; ++j)
        if (xsimd::any(groups[j].diffuse))
          add_light(c, f, c.lights[i], f.lights[i], overlaps.data() + n * (1 + k), groups[j]);
    }
    for (size_t j = 0; j < count; ++j) {
      Group& q = groups[j];
      if (!f.media.empty()) {
        B tr_r, tr_g, tr_b;
        f.media.transmittance(q.eye.x, q.eye.y, q.eye.z, q.p.x, q.p.y, q.p.z, q.valid, camera_overlaps, tr_r,
                              tr_g, tr_b);
        q.r *= tr_r, q.g *= tr_g, q.b *= tr_b;
      }
      const size_t at = size_t(gy[j]) * size_t(out.r.width) + size_t(gx[j]);
      xsimd::select(q.valid, q.r, B(0.0f)).store_unaligned(out.r.data.data() + at);
      xsimd::select(q.valid, q.g, B(0.0f)).store_unaligned(out.g.data.data() + at);
      xsimd::select(q.valid, q.b, B(0.0f)).store_unaligned(out.b.data.data() + at);
    }
    count = 0;
  };
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x + int(kLanes) <= x1; x += int(kLanes)) {
      const B depth = B::load_unaligned(c.g.depth.row(y) + x);
      if (!xsimd::any(depth < B(kSkyDepth))) {  // all sky: black
        B(0.0f).store_unaligned(out.r.row(y) + x);
        B(0.0f).store_unaligned(out.g.row(y) + x);
        B(0.0f).store_unaligned(out.b.row(y) + x);
        continue;
      }
      groups[count] = load_group(c, f, x, y, depth);
      gx[count] = x, gy[count] = y;
      if (++count == kBatch) flush();
    }
  flush();
}

}  // namespace caligo::shading
