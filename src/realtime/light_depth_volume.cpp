#include "realtime/light_depth_volume.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "realtime/directional_faces.h"
#include "realtime/media.h"

namespace caligo {

std::optional<LightDepthVolume> LightDepthVolume::build(const DirectionalLight& light, const VolumeScene& volumes,
                                                        int columns, int nodes) {
  LightDepthVolume v;
  v.held_.assign(volumes.primitives().size(), false);
  const View basis = light_basis(normalize(light.direction), 1);
  v.along_ = basis.forward;
  v.right_ = basis.right;
  v.up_ = basis.up;
  float lo[3] = {kInfinity, kInfinity, kInfinity}, hi[3] = {-kInfinity, -kInfinity, -kInfinity};
  std::vector<const VolumePrimitive*> grids;
  for (size_t i = 0; i < volumes.primitives().size(); ++i) {
    const VolumePrimitive& p = volumes.primitives()[i];
    if (!std::holds_alternative<GridDensity>(p.shader.field)) continue;
    v.held_[i] = true;
    grids.push_back(&p);
    const Bounds3 b = volume_bounds(p.shape);
    for (int c = 0; c < 8; ++c) {
      const Vec3 q = b.corner(c);
      const float x[3] = {dot(q, v.right_), dot(q, v.up_), dot(q, v.along_)};
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], x[k]), hi[k] = std::max(hi[k], x[k]);
    }
  }
  if (grids.empty()) return std::nullopt;
  v.nu_ = std::max(2, columns + 1);
  v.nw_ = std::max(2, nodes + 1);
  v.u0_ = lo[0], v.v0_ = lo[1], v.w0_ = lo[2];
  v.du_ = std::max(1e-6f, (hi[0] - lo[0]) / float(v.nu_ - 1));
  v.dv_ = std::max(1e-6f, (hi[1] - lo[1]) / float(v.nu_ - 1));
  v.dw_ = std::max(1e-6f, (hi[2] - lo[2]) / float(v.nw_ - 1));
  v.channels_ = 1;
  for (const VolumePrimitive* p : grids) {
    const RGB st = p->shader.sigma_a + p->shader.sigma_s;
    if (st.r != st.g || st.g != st.b) v.channels_ = 3;
  }
  const size_t nu = size_t(v.nu_), nw = size_t(v.nw_), ch = size_t(v.channels_);
  v.t_.assign(nu * nu * nw * ch, 1.0f);
  std::vector<float> nodes_t(nw);
  for (size_t k = 0; k < nw; ++k) nodes_t[k] = float(k) * v.dw_;
  parallel_for(v.nu_, [&](int j) {
    for (int i = 0; i < v.nu_; ++i) {
      // The column enters the bounds at node 0 and runs along the light.
      const Vec3 origin = v.right_ * (v.u0_ + float(i) * v.du_) + v.up_ * (v.v0_ + float(j) * v.dv_) +
                          v.along_ * v.w0_;
      float* column = &v.t_[(size_t(j) * nu + size_t(i)) * nw * ch];
      const Ray ray{origin, v.along_, 0.0f, float(nw - 1) * v.dw_};
      std::vector<RGB> tau(nw);
      for (const VolumePrimitive* p : grids) add_depth_profile(*p, ray, nodes_t, tau.data());
      for (size_t k = 1; k < nw; ++k) {
        const RGB t = exp_neg(tau[k]);
        for (size_t c = 0; c < ch; ++c) column[k * ch + c] = t[int(c)];
      }
    }
  });
  return v;
}

RGB LightDepthVolume::transmittance(Vec3 p) const {
  const float x = (dot(p, right_) - u0_) / du_, y = (dot(p, up_) - v0_) / dv_;
  const float last = float(nu_ - 1);
  if (!(x >= 0.0f && x <= last && y >= 0.0f && y <= last)) return RGB(1.0f);
  const float z = std::clamp((dot(p, along_) - w0_) / dw_, 0.0f, float(nw_ - 1));
  const int i = std::min(int(x), nu_ - 2), j = std::min(int(y), nu_ - 2), k = std::min(int(z), nw_ - 2);
  const float fx = x - float(i), fy = y - float(j), fz = z - float(k);
  const size_t nu = size_t(nu_), nw = size_t(nw_), ch = size_t(channels_);
  float out[3] = {1.0f, 1.0f, 1.0f};
  for (size_t c = 0; c < ch; ++c) {
    const auto column = [&](int cj, int ci) {
      const float* t = &t_[((size_t(cj) * nu + size_t(ci)) * nw + size_t(k)) * ch + c];
      return t[0] + (t[ch] - t[0]) * fz;
    };
    out[c] = (column(j, i) * (1.0f - fx) + column(j, i + 1) * fx) * (1.0f - fy) +
                  (column(j + 1, i) * (1.0f - fx) + column(j + 1, i + 1) * fx) * fy;
  }
  return ch == 1 ? RGB(out[0]) : RGB(out[0], out[1], out[2]);
}

}  // namespace caligo
