// The SIMD march of accumulate_light: 8 consecutive samples of one pixel per xsimd batch
// (AVX2 with -march=x86-64-v3). It re-implements the common cases of light_profile.h
// (inverse square, range window, cone smoothstep, box extent), of media.h (homogeneous
// and noise-modulated primitives, mean density for transmittance) and of the noise lookup
// lane-parallel; gobos and IES profiles fall back to the scalar delta_arrival per lane;
// shadow maps use shadow_map_simd.h's batch lookup. accumulate_test.cpp checks it against
// march_scalar.
#include <xsimd/xsimd.hpp>

#include <cmath>

#include "lights/light_profile.h"
#include "realtime/accumulate_internal.h"
#include "realtime/media.h"
#include "realtime/shadow_map_simd.h"

namespace caligo {

using Batch = xsimd::batch<float>;
using Mask = xsimd::batch_bool<float>;
constexpr int kLanes = int(Batch::size);

namespace {

enum class LightKind { point, spot, box, directional, unsupported };

struct BatchVec {
  Batch x, y, z;
};
inline Batch dot(const BatchVec& a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// A volume primitive reduced to what the lanes need: world -> object affine rows, its
// shape in object space and density-scaled coefficients.
struct LanePrimitive {
  bool sphere = false;  // unit sphere; else the box [lo, hi]
  float m[3][4];        // world -> object
  Vec3 lo, hi;
  RGB sigma_t, sigma_s;
  PhaseFunction phase;
  const NoiseModulation* noise = nullptr;

  BatchVec to_object(const BatchVec& p) const {
    return {p.x * m[0][0] + p.y * m[0][1] + p.z * m[0][2] + m[0][3],
            p.x * m[1][0] + p.y * m[1][1] + p.z * m[1][2] + m[1][3],
            p.x * m[2][0] + p.y * m[2][1] + p.z * m[2][2] + m[2][3]};
  }
  // Fraction in [0, 1] of the segment a -> b inside the primitive (segment parameter s is
  // the same in world and object space: the map is affine).
  Batch overlap_fraction(const BatchVec& a, const BatchVec& b) const {
    const BatchVec oa = to_object(a), ob = to_object(b);
    const BatchVec d{ob.x - oa.x, ob.y - oa.y, ob.z - oa.z};
    Batch s0(0.0f), s1(1.0f);
    if (sphere) {
      const Batch qa = d.x * d.x + d.y * d.y + d.z * d.z;
      const Batch qb = oa.x * d.x + oa.y * d.y + oa.z * d.z;
      const Batch qc = oa.x * oa.x + oa.y * oa.y + oa.z * oa.z - 1.0f;
      const Batch disc = qb * qb - qa * qc;
      const Batch root = xsimd::sqrt(xsimd::max(disc, Batch(0.0f)));
      const Batch inv = 1.0f / xsimd::max(qa, Batch(1e-30f));
      s0 = xsimd::max(s0, (-qb - root) * inv);
      s1 = xsimd::min(s1, (-qb + root) * inv);
      return xsimd::select(disc > 0.0f, xsimd::max(s1 - s0, Batch(0.0f)), Batch(0.0f));
    }
    const Batch oc[3] = {oa.x, oa.y, oa.z}, dc[3] = {d.x, d.y, d.z};
    for (int a = 0; a < 3; ++a) {
      // A tiny denominator instead of 0 keeps every lane finite (no inf * 0).
      const Batch dd = xsimd::select(xsimd::abs(dc[a]) < 1e-20f, Batch(1e-20f), dc[a]);
      const Batch inv = 1.0f / dd;
      const Batch tn = (lo[a] - oc[a]) * inv, tf = (hi[a] - oc[a]) * inv;
      s0 = xsimd::max(s0, xsimd::min(tn, tf));
      s1 = xsimd::min(s1, xsimd::max(tn, tf));
    }
    return xsimd::max(s1 - s0, Batch(0.0f));
  }
};

// Henyey-Greenstein written as phase.cpp's henyey_greenstein (same branch on the sign of g).
Batch hg(const Batch& cos_theta, float g) {
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

Batch exp_neg(const Batch& tau) { return xsimd::exp(-tau); }

// volumes/noise.cpp's NoiseTexture::lookup and noise_density, lane-parallel (the same
// arithmetic in the same order, with gathers for the lattice values).
using IBatch = xsimd::batch<int32_t>;
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
    return Batch::gather(values, index);
  };
  auto lerp = [](const Batch& w, const Batch& a, const Batch& b) { return (1.0f - w) * a + w * b; };
  const Batch x00 = lerp(t[0], at(0, 0, 0), at(1, 0, 0));
  const Batch x10 = lerp(t[0], at(0, 1, 0), at(1, 1, 0));
  const Batch x01 = lerp(t[0], at(0, 0, 1), at(1, 0, 1));
  const Batch x11 = lerp(t[0], at(0, 1, 1), at(1, 1, 1));
  return lerp(t[2], lerp(t[1], x00, x10), lerp(t[1], x01, x11));
}

Batch noise_density_batch(const NoiseModulation& noise, const Batch& px, const Batch& py, const Batch& pz) {
  const float* values = NoiseTexture::shared().values().data();
  const Batch qx = (px - noise.offset.x) * noise.scale, qy = (py - noise.offset.y) * noise.scale,
              qz = (pz - noise.offset.z) * noise.scale;
  const Batch fbm =
      (2.0f / 3.0f) * noise_lookup(values, qx, qy, qz) +
      (1.0f / 3.0f) * noise_lookup(values, qx * 2.0f + 11.37f, qy * 2.0f + 5.71f, qz * 2.0f + 17.13f);
  return xsimd::max(Batch(0.0f), 1.0f + noise.amplitude * fbm);
}

}  // namespace

struct SimdMarcher::Data {
  const FrameLight* light = nullptr;
  LightKind kind = LightKind::unsupported;
  bool scalar_arrival = false;  // gobo or IES: delta_arrival per lane
  Vec3 position, direction, up, right;
  float cos_inner = 1.0f, cos_outer = 0.0f, range = kInfinity, inv_range = 0.0f;
  float half_width = 0.0f, half_height = 0.0f;
  RGB color;
  std::vector<LanePrimitive> prims;
  bool grey = true;  // every sigma_t grey: one exp per sample instead of three
  float floor = 0.0f, far = 0.0f;

  // Light arriving at the lanes' points: direction to the light, distance, radiance.
  struct LaneArrival {
    BatchVec wi;
    Batch dist, r, g, b;
  };
  LaneArrival arrival(const BatchVec& p) const;
  LaneArrival arrival_scalar(const BatchVec& p) const;
};

namespace {

// Fills the light part of Data; false for lights the SIMD path does not handle.
struct DescribeLight {
  SimdMarcher::Data& d;
  static float inv(float range) { return std::isfinite(range) ? 1.0f / range : 0.0f; }
  void operator()(const PointLight& l) const {
    d.kind = LightKind::point;
    d.position = l.position;
    d.range = l.range;
    d.inv_range = inv(l.range);
    d.color = l.intensity;
    d.scalar_arrival = bool(l.ies.profile);
  }
  void operator()(const SpotLight& l) const {
    d.kind = LightKind::spot;
    d.position = l.position;
    d.direction = l.direction;
    d.cos_inner = l.cos_inner;
    d.cos_outer = l.cos_outer;
    d.range = l.range;
    d.inv_range = inv(l.range);
    d.color = l.intensity;
    d.scalar_arrival = bool(l.ies.profile) || bool(l.gobo.image);
  }
  void operator()(const BoxLight& l) const {
    d.kind = LightKind::box;
    d.position = l.position;
    d.direction = l.direction;
    d.up = l.up;
    d.right = cross(l.direction, l.up);
    d.half_width = l.half_width;
    d.half_height = l.half_height;
    d.range = l.range;
    d.color = l.irradiance;
    d.scalar_arrival = bool(l.gobo.image);
  }
  void operator()(const DirectionalLight& l) const {
    d.kind = LightKind::directional;
    d.direction = l.direction;
    d.color = l.irradiance;
  }
  void operator()(const SphereLight&) const { d.kind = LightKind::unsupported; }
  void operator()(const QuadLight&) const { d.kind = LightKind::unsupported; }
  void operator()(const TriangleLight&) const { d.kind = LightKind::unsupported; }
  void operator()(const EnvironmentLight&) const { d.kind = LightKind::unsupported; }
};

// Object-space description of a primitive for the lanes; false for density fields the
// SIMD path does not integrate (radial falloff).
bool describe_primitive(const VolumePrimitive& prim, LanePrimitive& out) {
  if (!has_constant_field(prim.shader)) return false;
  const Mat4* inv = nullptr;
  if (const auto* s = std::get_if<SphereVolumeShape>(&prim.shape)) {
    out.sphere = true;
    inv = &s->sphere.object_to_world.inverse_matrix();
  } else {
    const auto& b = std::get<BoxVolumeShape>(prim.shape);
    out.sphere = false;
    out.lo = b.lo;
    out.hi = b.hi;
    inv = &b.object_to_world.inverse_matrix();
  }
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) out.m[r][c] = inv->m[r][c];
  out.sigma_t = (prim.shader.sigma_a + prim.shader.sigma_s) * prim.shader.density;
  out.sigma_s = prim.shader.sigma_s * prim.shader.density;
  out.phase = prim.shader.phase;
  out.noise = prim.shader.noise ? &*prim.shader.noise : nullptr;
  return true;
}

Batch range_window(const Batch& dist, float range, float inv_range) {
  if (!std::isfinite(range)) return Batch(1.0f);
  const Batch x = dist * inv_range;
  const Batch x2 = x * x;
  const Batch w = 1.0f - x2 * x2;
  return xsimd::select(dist < range, w * w, Batch(0.0f));
}

Batch smoothstep(float e0, float e1, const Batch& x) {
  if (e0 == e1) return xsimd::select(x < e0, Batch(0.0f), Batch(1.0f));
  const Batch t = xsimd::min(xsimd::max((x - e0) / (e1 - e0), Batch(0.0f)), Batch(1.0f));
  return t * t * (3.0f - 2.0f * t);
}

}  // namespace

SimdMarcher::Data::LaneArrival SimdMarcher::Data::arrival_scalar(const BatchVec& p) const {
  alignas(32) float px[kLanes], py[kLanes], pz[kLanes];
  alignas(32) float out[7][kLanes];
  p.x.store_aligned(px);
  p.y.store_aligned(py);
  p.z.store_aligned(pz);
  for (int i = 0; i < kLanes; ++i) {
    const Vec3 q{px[i], py[i], pz[i]};
    std::optional<DeltaArrival> a;
    if (const auto* l = std::get_if<PointLight>(&light->light))
      a = delta_arrival(*l, q);
    else if (const auto* s = std::get_if<SpotLight>(&light->light))
      a = delta_arrival(*s, q);
    else if (const auto* b = std::get_if<BoxLight>(&light->light))
      a = delta_arrival(*b, q);
    const DeltaArrival v = a.value_or(DeltaArrival{RGB(0.0f), Vec3(0.0f, 0.0f, 1.0f), 0.0f});
    const float vals[7] = {v.wi.x, v.wi.y, v.wi.z, v.distance, v.radiance.r, v.radiance.g, v.radiance.b};
    for (int c = 0; c < 7; ++c) out[c][i] = vals[c];
  }
  auto ld = [&](int c) { return Batch::load_aligned(out[c]); };
  return {{ld(0), ld(1), ld(2)}, ld(3), ld(4), ld(5), ld(6)};
}

SimdMarcher::Data::LaneArrival SimdMarcher::Data::arrival(const BatchVec& p) const {
  if (scalar_arrival) return arrival_scalar(p);
  LaneArrival a;
  Batch scale;
  switch (kind) {
    case LightKind::point:
    case LightKind::spot: {
      const BatchVec d{position.x - p.x, position.y - p.y, position.z - p.z};
      const Batch dist2 = d.x * d.x + d.y * d.y + d.z * d.z;
      a.dist = xsimd::sqrt(dist2);
      const Batch inv = 1.0f / a.dist;
      a.wi = {d.x * inv, d.y * inv, d.z * inv};
      scale = range_window(a.dist, range, inv_range) / dist2;
      if (kind == LightKind::spot) scale *= smoothstep(cos_outer, cos_inner, -dot(a.wi, direction));
      scale = xsimd::select(dist2 > 0.0f, scale, Batch(0.0f));
      break;
    }
    case LightKind::box: {
      const BatchVec l{p.x - position.x, p.y - position.y, p.z - position.z};
      const Batch along = dot(l, direction);
      const Batch x = dot(l, right), y = dot(l, up);
      const Mask inside =
          (along >= 0.0f) & (along <= range) & (xsimd::abs(x) <= half_width) & (xsimd::abs(y) <= half_height);
      a.wi = {Batch(-direction.x), Batch(-direction.y), Batch(-direction.z)};
      a.dist = along;
      scale = xsimd::select(inside, Batch(1.0f), Batch(0.0f));
      break;
    }
    case LightKind::directional:
    case LightKind::unsupported:
      a.wi = {Batch(-direction.x), Batch(-direction.y), Batch(-direction.z)};
      a.dist = Batch(kInfinity);
      scale = Batch(1.0f);
      break;
  }
  a.r = scale * color.r;
  a.g = scale * color.g;
  a.b = scale * color.b;
  return a;
}

SimdMarcher::SimdMarcher(const FrameLight& light, const VolumeScene& volumes, float multiple_scattering_floor,
                         float far)
    : data_(std::make_unique<Data>()) {
  Data& d = *data_;
  d.light = &light;
  d.floor = multiple_scattering_floor;
  d.far = far;
  std::visit(DescribeLight{d}, light.light);
  supported_ = d.kind != LightKind::unsupported;
  d.prims.resize(volumes.primitives().size());
  for (size_t i = 0; i < d.prims.size(); ++i) {
    supported_ = supported_ && describe_primitive(volumes.primitives()[i], d.prims[i]);
    const RGB st = d.prims[i].sigma_t;
    d.grey = d.grey && st.r == st.g && st.g == st.b;
  }
}

SimdMarcher::~SimdMarcher() = default;

RGB SimdMarcher::march(const PixelMarch& m) const {
  const Data& d = *data_;
  alignas(32) static constexpr float kLaneIndex[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  static_assert(kLanes == 8, "built for AVX2 (-march=x86-64-v3)");
  const Batch lane = Batch::load_aligned(kLaneIndex);
  Batch sum_r(0.0f), sum_g(0.0f), sum_b(0.0f);
  for (int k0 = 0; k0 < m.samples; k0 += kLanes) {
    const Batch k = lane + float(k0);
    const Batch t = m.t0 + (k + m.offset) * m.step;
    const BatchVec p{m.origin.x + m.dir.x * t, m.origin.y + m.dir.y * t, m.origin.z + m.dir.z * t};
    const Data::LaneArrival a = d.arrival(p);
    Mask ok = (k < float(m.samples)) & ((a.r > 0.0f) | (a.g > 0.0f) | (a.b > 0.0f));
    if (xsimd::none(ok)) continue;

    // Scattering (sigma_s x phase, summed over the primitives here) and camera optical depth.
    const Batch cos_theta = xsimd::min(xsimd::max(dot(a.wi, m.dir), Batch(-1.0f)), Batch(1.0f));
    Batch s_r(0.0f), s_g(0.0f), s_b(0.0f);
    Batch tau_r(0.0f), tau_g(0.0f), tau_b(0.0f);
    for (const VolumeInterval& iv : *m.intervals) {
      const LanePrimitive& prim = d.prims[iv.primitive];
      const Mask in = (t >= iv.t0) & (t <= iv.t1);
      const Batch covered = xsimd::min(xsimd::max(t - iv.t0, Batch(0.0f)), Batch(iv.t1 - iv.t0));
      tau_r += covered * prim.sigma_t.r;
      if (!d.grey) {
        tau_g += covered * prim.sigma_t.g;
        tau_b += covered * prim.sigma_t.b;
      }
      if (xsimd::none(in)) continue;
      Batch w = xsimd::select(in, std::visit(PhaseBatch{cos_theta}, prim.phase), Batch(0.0f));
      if (prim.noise) w *= noise_density_batch(*prim.noise, p.x, p.y, p.z);
      s_r += w * prim.sigma_s.r;
      s_g += w * prim.sigma_s.g;
      s_b += w * prim.sigma_s.b;
    }
    ok = ok & ((s_r > 0.0f) | (s_g > 0.0f) | (s_b > 0.0f));
    if (xsimd::none(ok)) continue;

    // Optical depth towards the light, through every primitive of the scene.
    const Batch reach = xsimd::min(a.dist, Batch(d.far));
    const BatchVec q{p.x + a.wi.x * reach, p.y + a.wi.y * reach, p.z + a.wi.z * reach};
    for (const LanePrimitive& prim : d.prims) {
      const Batch len = prim.overlap_fraction(p, q) * reach;
      tau_r += len * prim.sigma_t.r;
      if (!d.grey) {
        tau_g += len * prim.sigma_t.g;
        tau_b += len * prim.sigma_t.b;
      }
    }

    Batch v(1.0f);
    if (d.light->shadow) v = xsimd::max(shadow_visibility(*d.light->shadow, p.x, p.y, p.z), Batch(d.floor));
    const Batch tr_r = exp_neg(tau_r);
    const Batch tr_g = d.grey ? tr_r : exp_neg(tau_g);
    const Batch tr_b = d.grey ? tr_r : exp_neg(tau_b);
    sum_r += xsimd::select(ok, s_r * a.r * tr_r * v, Batch(0.0f));
    sum_g += xsimd::select(ok, s_g * a.g * tr_g * v, Batch(0.0f));
    sum_b += xsimd::select(ok, s_b * a.b * tr_b * v, Batch(0.0f));
  }
  return RGB(xsimd::hadd(sum_r), xsimd::hadd(sum_g), xsimd::hadd(sum_b)) * m.step;
}

}  // namespace caligo
