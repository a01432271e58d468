// The SIMD march of accumulate_light: 8 consecutive samples of one pixel per xsimd batch
// (AVX2 with -march=x86-64-v3). The light arrives through light_lanes.h (light_profile.h's
// delta_arrival lane-parallel: inverse square, range window, cone, box extent, gobos and IES
// profiles), the media through accumulate_lanes.h, and shadow maps through
// shadow_map_simd.h (single-face maps through ShadowRaySimd, whose texel coordinates are
// prepared once per pixel ray). accumulate_test.cpp checks it against march_scalar.
#include <xsimd/xsimd.hpp>

#include <cmath>
#include <optional>

#include "realtime/accumulate_internal.h"
#include "realtime/accumulate_lanes.h"
#include "realtime/light_lanes.h"
#include "realtime/shadow_map_simd.h"

namespace caligo {

using lanes::Batch;
using lanes::BatchVec;
using lanes::Mask;
constexpr int kLanes = int(Batch::size);
alignas(32) constexpr float kLaneIndex[8] = {0, 1, 2, 3, 4, 5, 6, 7};

namespace lanes {

bool describe_primitive(const VolumePrimitive& prim, Primitive& out) {
  if (!has_constant_field(prim)) return false;
  static_cast<ObjectSpaceShape&>(out) = object_space_shape(prim.shape);
  out.sigma_t = (prim.shader.sigma_a + prim.shader.sigma_s) * prim.shader.density;
  out.sigma_s = prim.shader.sigma_s * prim.shader.density;
  out.phase = prim.shader.phase;
  out.noise = prim.shader.noise ? &*prim.shader.noise : nullptr;
  return true;
}

LightSide LightSide::parallel_light(const Primitive& prim, Vec3 wi) {
  LightSide s;
  s.parallel = true;
  s.d = prim.to_object_dir(wi);
  s.inv = {safe_reciprocal(s.d.x), safe_reciprocal(s.d.y), safe_reciprocal(s.d.z)};
  s.qa = std::max(length_squared(s.d), 1e-30f);
  s.inv_qa = 1.0f / s.qa;
  return s;
}

LightSide LightSide::point_light(const Primitive& prim, const VolumePrimitive& source, Vec3 position) {
  LightSide s;
  s.light_inside = prim.contains_object(prim.to_object(position));
  // The bounding ball of the primitive's world bounds, and the cone of directions from the
  // light that can meet it (widened by 1e-4 in cosine against rounding).
  const Bounds3 b = volume_bounds(source.shape);
  const Vec3 centre = (b.lo + b.hi) * 0.5f;
  const float radius = 0.5f * length(b.diagonal());
  const float dist = distance(centre, position);
  if (dist > radius * 1.001f) {
    s.cone_cull = true;
    s.cone_axis = (centre - position) / dist;
    s.cone_cos = std::sqrt(1.0f - sqr(radius / dist)) - 1e-4f;
  }
  return s;
}

// volumes/noise.cpp's NoiseTexture::lookup and noise_density, lane-parallel (the same
// arithmetic in the same order, with AVX2 gathers for the lattice values).
namespace {

constexpr int kNoiseN = NoiseTexture::kSize;

Batch noise_lookup(const float* values, const Batch& x, const Batch& y, const Batch& z) {
  IBatch cell[3];
  Batch t[3];
  const Batch coord[3] = {x, y, z};
  for (int a = 0; a < 3; ++a) {
    const Batch r = coord[a] - float(kNoiseN) * xsimd::floor(coord[a] / float(kNoiseN));
    const Batch f = xsimd::floor(r);
    cell[a] = xsimd::batch_cast<int32_t>(f) & IBatch(kNoiseN - 1);
    const Batch u = xsimd::min(xsimd::max(r - f, Batch(0.0f)), Batch(1.0f));
    t[a] = u * u * u * (u * (u * 6.0f - 15.0f) + 10.0f);
  }
  const IBatch mask(kNoiseN - 1);
  auto at = [&](int dx, int dy, int dz) {
    const IBatch index =
        (((cell[2] + dz) & mask) * kNoiseN + ((cell[1] + dy) & mask)) * kNoiseN + ((cell[0] + dx) & mask);
    return Batch(_mm256_i32gather_ps(values, index, 4));
  };
  auto lerp = [](const Batch& w, const Batch& a, const Batch& b) { return (1.0f - w) * a + w * b; };
  const Batch x00 = lerp(t[0], at(0, 0, 0), at(1, 0, 0));
  const Batch x10 = lerp(t[0], at(0, 1, 0), at(1, 1, 0));
  const Batch x01 = lerp(t[0], at(0, 0, 1), at(1, 0, 1));
  const Batch x11 = lerp(t[0], at(0, 1, 1), at(1, 1, 1));
  return lerp(t[2], lerp(t[1], x00, x10), lerp(t[1], x01, x11));
}

}  // namespace

Batch noise_density_batch(const NoiseModulation& noise, const Batch& px, const Batch& py, const Batch& pz) {
  const float* values = NoiseTexture::shared().values().data();
  const Batch qx = (px - noise.offset.x) * noise.scale, qy = (py - noise.offset.y) * noise.scale,
              qz = (pz - noise.offset.z) * noise.scale;
  const Batch fbm =
      (2.0f / 3.0f) * noise_lookup(values, qx, qy, qz) +
      (1.0f / 3.0f) * noise_lookup(values, qx * 2.0f + 11.37f, qy * 2.0f + 5.71f, qz * 2.0f + 17.13f);
  return xsimd::max(Batch(0.0f), 1.0f + noise.amplitude * fbm);
}

}  // namespace lanes

struct SimdMarcher::Data {
  const FrameLight* light = nullptr;
  std::optional<LightLanes> arrivals;  // the light, prepared for 8-lane arrival
  std::vector<lanes::Primitive> prims;
  std::vector<lanes::LightSide> sides;  // per primitive, for this light
  bool grey = true;                     // every sigma_t grey: one exp per sample instead of three
  bool any_light_inside = false;        // some side needs the camera's inside masks
  float floor = 0.0f, far = 0.0f;

  // Light arriving at the lanes' points: direction to the light, distance, radiance.
  struct LaneArrival {
    BatchVec wi;
    Batch dist, r, g, b;
  };
  LaneArrival arrival(const BatchVec& p) const;
};

SimdMarcher::Data::LaneArrival SimdMarcher::Data::arrival(const BatchVec& p) const {
  const LightLanes::Arrival a = arrivals->at(p.x, p.y, p.z);
  return {{a.wx, a.wy, a.wz}, a.distance, a.r, a.g, a.b};
}

SimdMarcher::SimdMarcher(const FrameLight& light, const VolumeScene& volumes, float multiple_scattering_floor,
                         float far)
    : data_(std::make_unique<Data>()) {
  Data& d = *data_;
  d.light = &light;
  d.floor = multiple_scattering_floor;
  d.far = far;
  d.arrivals.emplace(light.light);
  supported_ = true;
  d.prims.resize(volumes.primitives().size());
  for (size_t i = 0; i < d.prims.size(); ++i) {
    supported_ = supported_ && lanes::describe_primitive(volumes.primitives()[i], d.prims[i]);
    const RGB st = d.prims[i].sigma_t;
    d.grey = d.grey && st.r == st.g && st.g == st.b;
  }
  if (!supported_) return;
  const bool parallel = d.arrivals->parallel();
  for (size_t i = 0; i < d.prims.size(); ++i) {
    d.sides.push_back(parallel ? lanes::LightSide::parallel_light(d.prims[i], -d.arrivals->direction())
                               : lanes::LightSide::point_light(d.prims[i], volumes.primitives()[i],
                                                               d.arrivals->position()));
    d.any_light_inside = d.any_light_inside || d.sides.back().light_inside;
  }
}

SimdMarcher::~SimdMarcher() = default;

namespace {

// Which primitives hold which lanes' points, from the camera's intervals (the first few
// primitives only: enough for real-time scenes, and the others just take the general test).
constexpr size_t kInsideSlots = 16;

// march_sample for 8 samples k (lane-parallel): positions on the ray and quadrature weights.
Batch sample_t(const PixelMarch& m, const Batch& k, Batch& weight) {
  if (!m.equiangular) {
    weight = Batch(m.step);
    return m.t0 + (k + m.offset) * m.step;
  }
  const Batch x = m.D * xsimd::tan(m.theta0 + (k + m.offset) * m.dtheta);
  weight = (m.dtheta / m.D) * (m.D * m.D + x * x);
  return m.tc + x;
}

}  // namespace

void SimdMarcher::prefetch(const PixelMarch& m) const {
  const ShadowMap* map = data_->light->shadow;
  if (!map) return;
  const Batch lane = Batch::load_aligned(kLaneIndex);
  if (ShadowRaySimd::applies(*map)) {
    const ShadowRaySimd shadow(*map, m.origin, m.dir);
    for (int k0 = 0; k0 < m.samples; k0 += kLanes) {
      alignas(32) int32_t index[kLanes];
      Batch unused_weight;
      shadow.texels(sample_t(m, lane + float(k0), unused_weight)).store_aligned(index);
      const int lanes_here = std::min(kLanes, m.samples - k0);
      for (int i = 0; i < lanes_here; ++i)
        _mm_prefetch(reinterpret_cast<const char*>(shadow.data() + index[i]), _MM_HINT_T0);
    }
    return;
  }
  for (int k0 = 0; k0 < m.samples; k0 += kLanes) {
    Batch unused_weight;
    const Batch t = sample_t(m, lane + float(k0), unused_weight);
    const Batch px = m.origin.x + m.dir.x * t, py = m.origin.y + m.dir.y * t, pz = m.origin.z + m.dir.z * t;
    const int face = shadow_detail::common_face(*map, px, py, pz);
    if (face < 0) continue;
    // The texel face_visibility will read (clamped into the face; only a hint).
    const View& v = map->faces[size_t(face)];
    const Plane& depth = map->depth[size_t(face)];
    const Batch dx = px - v.eye.x, dy = py - v.eye.y, dz = pz - v.eye.z;
    const Batch xr = dx * v.right.x + dy * v.right.y + dz * v.right.z;
    const Batch yu = dx * v.up.x + dy * v.up.y + dz * v.up.z;
    Batch ndc_x, ndc_y;
    if (v.projection == Projection::perspective) {
      const Batch z = xsimd::max(dx * v.forward.x + dy * v.forward.y + dz * v.forward.z, Batch(1e-6f));
      const Batch inv = 1.0f / (z * v.tan_half_fov_y);
      ndc_x = xr * inv / v.aspect;
      ndc_y = yu * inv;
    } else {
      ndc_x = xr / v.half_width;
      ndc_y = yu / v.half_height;
    }
    const float w = float(depth.width), h = float(depth.height);
    const Batch fx = xsimd::clip(xsimd::floor((ndc_x + 1.0f) * (0.5f * w)), Batch(0.0f), Batch(w - 1.0f));
    const Batch fy = xsimd::clip(xsimd::floor((1.0f - ndc_y) * (0.5f * h)), Batch(0.0f), Batch(h - 1.0f));
    alignas(32) int32_t index[kLanes];
    (xsimd::batch_cast<int32_t>(fy) * depth.width + xsimd::batch_cast<int32_t>(fx)).store_aligned(index);
    const int lanes_here = std::min(kLanes, m.samples - k0);
    for (int i = 0; i < lanes_here; ++i)
      _mm_prefetch(reinterpret_cast<const char*>(depth.data.data() + index[i]), _MM_HINT_T0);
  }
}

namespace {

// One batch of samples along the pixel's ray: sigma_s x phase summed over the primitives at
// the lanes' points (overlapping media add their coefficients and mix their phases in
// proportion to sigma_s), the camera optical depth to them, and which of the first `slots`
// primitives hold each lane.
struct BatchScatter {
  Batch s_r = Batch(0.0f), s_g = Batch(0.0f), s_b = Batch(0.0f);
  Batch tau_r = Batch(0.0f), tau_g = Batch(0.0f), tau_b = Batch(0.0f);
};

BatchScatter scatter_and_camera_depth(const SimdMarcher::Data& d, const PixelMarch& m, const Batch& t,
                                      const BatchVec& p, const Batch& cos_theta, const Batch* hoisted_phase,
                                      const Mask& ok, Mask* inside, size_t slots) {
  BatchScatter out;
  for (size_t i = 0; i < slots; ++i) inside[i] = Mask(false);
  for (size_t j = 0; j < m.intervals.size(); ++j) {
    const VolumeInterval& iv = m.intervals[j];
    const lanes::Primitive& prim = d.prims[iv.primitive];
    const Mask in = (t >= iv.t0) & (t <= iv.t1);
    if (iv.primitive < slots) inside[iv.primitive] = in;
    const Batch covered = xsimd::min(xsimd::max(t - iv.t0, Batch(0.0f)), Batch(iv.t1 - iv.t0));
    out.tau_r += covered * prim.sigma_t.r;
    if (!d.grey) {
      out.tau_g += covered * prim.sigma_t.g;
      out.tau_b += covered * prim.sigma_t.b;
    }
    if (xsimd::none(in & ok)) continue;
    Batch w = xsimd::select(
        in, hoisted_phase ? hoisted_phase[j] : std::visit(lanes::PhaseBatch{cos_theta}, prim.phase), Batch(0.0f));
    if (prim.noise) w *= lanes::noise_density_batch(*prim.noise, p.x, p.y, p.z);
    out.s_r += w * prim.sigma_s.r;
    out.s_g += w * prim.sigma_s.g;
    out.s_b += w * prim.sigma_s.b;
  }
  return out;
}

// Adds the optical depth towards the light, through every primitive of the scene, to `bs`.
void add_light_depth(const SimdMarcher::Data& d, const BatchVec& p, const SimdMarcher::Data::LaneArrival& a,
                     const Mask* inside, size_t slots, const Mask& ok, BatchScatter& bs) {
  const Batch reach = xsimd::min(a.dist, Batch(d.far));
  for (size_t i = 0; i < d.prims.size(); ++i) {
    const Batch len = d.sides[i].overlap(d.prims[i], p, a.wi, reach, i < slots ? inside[i] : Mask(false), ok);
    bs.tau_r += len * d.prims[i].sigma_t.r;
    if (!d.grey) {
      bs.tau_g += len * d.prims[i].sigma_t.g;
      bs.tau_b += len * d.prims[i].sigma_t.b;
    }
  }
}

}  // namespace

namespace {

// What one batch of samples at t sends towards the camera, per lane: sigma_s x phase x the
// light's arrival x shadow x e^(-tau), tau towards the light, plus the camera's when kCamera;
// lanes outside `ok` (or unlit, or in no medium) end outside out.ok.
struct LaneLight {
  Batch r, g, b;
  Mask ok;
};

struct RayPrep {
  std::optional<ShadowRaySimd> shadow_ray;
  bool hoist_phase = false;
  static constexpr size_t kPhaseSlots = 8;
  Batch phase[kPhaseSlots];
  Mask inside[kInsideSlots];
  size_t slots = 0;
};

// Directional and box lights arrive from one direction everywhere, so the scattering angle is
// the same at every sample of the ray: each primitive's phase once per ray.
void prepare_ray(const SimdMarcher::Data& d, const PixelMarch& m, RayPrep& prep) {
  prep.slots = d.any_light_inside ? std::min(kInsideSlots, d.prims.size()) : 0;
  prep.hoist_phase = d.arrivals->parallel() && m.intervals.size() <= RayPrep::kPhaseSlots;
  const ShadowMap* map = d.light->shadow;
  if (map && ShadowRaySimd::applies(*map)) prep.shadow_ray.emplace(*map, m.origin, m.dir);
  if (!prep.hoist_phase) return;
  const Vec3 wi = -d.arrivals->direction();
  const Batch cos_theta = xsimd::min(xsimd::max(Batch(dot(wi, m.dir)), Batch(-1.0f)), Batch(1.0f));
  for (size_t j = 0; j < m.intervals.size(); ++j)
    prep.phase[j] = std::visit(lanes::PhaseBatch{cos_theta}, d.prims[m.intervals[j].primitive].phase);
}

template <bool kCamera>
LaneLight sample_lanes(const SimdMarcher::Data& d, const PixelMarch& m, const Batch& t, Mask ok, RayPrep& prep) {
  LaneLight out{Batch(0.0f), Batch(0.0f), Batch(0.0f), Mask(false)};
  const BatchVec p{m.origin.x + m.dir.x * t, m.origin.y + m.dir.y * t, m.origin.z + m.dir.z * t};
  const SimdMarcher::Data::LaneArrival a = d.arrival(p);
  ok = ok & ((a.r > 0.0f) | (a.g > 0.0f) | (a.b > 0.0f));
  if (xsimd::none(ok)) return out;
  const Batch cos_theta = xsimd::min(xsimd::max(lanes::dot(a.wi, m.dir), Batch(-1.0f)), Batch(1.0f));
  BatchScatter bs = scatter_and_camera_depth(d, m, t, p, cos_theta, prep.hoist_phase ? prep.phase : nullptr, ok,
                                             prep.inside, prep.slots);
  if (!kCamera) bs.tau_r = bs.tau_g = bs.tau_b = Batch(0.0f);
  ok = ok & ((bs.s_r > 0.0f) | (bs.s_g > 0.0f) | (bs.s_b > 0.0f));
  if (xsimd::none(ok)) return out;
  // The shadow map before the light's optical depth: shadowed lanes need no segment.
  Batch v(1.0f);
  if (const ShadowMap* map = d.light->shadow) {
    v = xsimd::max(prep.shadow_ray ? prep.shadow_ray->visibility(t) : shadow_visibility(*map, p.x, p.y, p.z),
                   Batch(d.floor));
    ok = ok & (v > 0.0f);
    if (xsimd::none(ok)) return out;
  }
  add_light_depth(d, p, a, prep.inside, prep.slots, ok, bs);
  const Batch tr_r = lanes::exp_neg(bs.tau_r);
  const Batch tr_g = d.grey ? tr_r : lanes::exp_neg(bs.tau_g);
  const Batch tr_b = d.grey ? tr_r : lanes::exp_neg(bs.tau_b);
  out.r = bs.s_r * a.r * tr_r * v;
  out.g = bs.s_g * a.g * tr_g * v;
  out.b = bs.s_b * a.b * tr_b * v;
  out.ok = ok;
  return out;
}

}  // namespace

RGB SimdMarcher::march(const PixelMarch& m) const {
  static_assert(kLanes == 8, "built for AVX2 (-march=x86-64-v3)");
  const Batch lane = Batch::load_aligned(kLaneIndex);
  Batch sum_r(0.0f), sum_g(0.0f), sum_b(0.0f);
  RayPrep prep;
  prepare_ray(*data_, m, prep);
  for (int k0 = 0; k0 < m.samples; k0 += kLanes) {
    const Batch k = lane + float(k0);
    Batch weight;
    const Batch t = sample_t(m, k, weight);
    const LaneLight l = sample_lanes<true>(*data_, m, t, k < float(m.samples), prep);
    sum_r += xsimd::select(l.ok, l.r * weight, Batch(0.0f));
    sum_g += xsimd::select(l.ok, l.g * weight, Batch(0.0f));
    sum_b += xsimd::select(l.ok, l.b * weight, Batch(0.0f));
  }
  return RGB(xsimd::hadd(sum_r), xsimd::hadd(sum_g), xsimd::hadd(sum_b));
}

void SimdMarcher::inscatter(const PixelMarch& m, std::span<const float> t, RGB* out) const {
  const Batch lane = Batch::load_aligned(kLaneIndex);
  RayPrep prep;
  prepare_ray(*data_, m, prep);
  const int n = int(t.size());
  for (int k0 = 0; k0 < n; k0 += kLanes) {
    alignas(32) float ts[kLanes], r[kLanes], g[kLanes], b[kLanes];
    for (int i = 0; i < kLanes; ++i) ts[i] = t[size_t(std::min(k0 + i, n - 1))];
    const LaneLight l = sample_lanes<false>(*data_, m, Batch::load_aligned(ts), lane + float(k0) < float(n), prep);
    xsimd::select(l.ok, l.r, Batch(0.0f)).store_aligned(r);
    xsimd::select(l.ok, l.g, Batch(0.0f)).store_aligned(g);
    xsimd::select(l.ok, l.b, Batch(0.0f)).store_aligned(b);
    for (int i = 0; i < std::min(kLanes, n - k0); ++i) out[k0 + i] += RGB(r[i], g[i], b[i]);
  }
}

}  // namespace caligo
