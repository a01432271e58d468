#include "materials/bsdf.h"

#include <cmath>

#include "core/math.h"
#include "core/sampling.h"

namespace caligo {

float fresnel_dielectric(float cos_i, float eta) {
  cos_i = std::clamp(cos_i, -1.0f, 1.0f);
  if (cos_i < 0.0f) {
    eta = 1.0f / eta;
    cos_i = -cos_i;
  }
  const float sin2_t = (1.0f - sqr(cos_i)) / sqr(eta);
  if (sin2_t >= 1.0f) return 1.0f;  // total internal reflection
  const float cos_t = safe_sqrt(1.0f - sin2_t);
  const float r_parallel = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const float r_perpendicular = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (sqr(r_parallel) + sqr(r_perpendicular));
}

namespace {

Vec3 reflect(Vec3 wo, Vec3 n) { return -wo + n * (2.0f * dot(wo, n)); }

// Refracts wo through a surface with normal n on wo's side; eta = n_transmitted / n_incident.
std::optional<Vec3> refract(Vec3 wo, Vec3 n, float eta) {
  const float cos_i = dot(n, wo);
  const float sin2_t = (1.0f - sqr(cos_i)) / sqr(eta);
  if (sin2_t >= 1.0f) return std::nullopt;
  const float cos_t = safe_sqrt(1.0f - sin2_t);
  return normalize(-wo / eta + n * (cos_i / eta - cos_t));
}

// Each visitor has one overload per Bsdf member and no `auto` catch-all, so adding a member
// (material.h) is a compile error here until it is handled.
struct Eval {
  Vec3 n, wo, wi;
  RGB operator()(const DiffuseBsdf& b) const {
    // Reflection only: both directions on the same side of the surface.
    if (dot(n, wo) * dot(n, wi) <= 0.0f) return RGB(0.0f);
    return b.reflectance * kInvPi;
  }
  // Deltas (dielectric, null) have no finite value for any pair of directions.
  RGB operator()(const DielectricBsdf&) const { return RGB(0.0f); }
  RGB operator()(const BlackBsdf&) const { return RGB(0.0f); }
  RGB operator()(const NullBsdf&) const { return RGB(0.0f); }
};

struct Pdf {
  Vec3 n, wo, wi;
  float operator()(const DiffuseBsdf&) const {
    if (dot(n, wo) * dot(n, wi) <= 0.0f) return 0.0f;
    return cosine_hemisphere_pdf(abs_dot(n, wi));
  }
  float operator()(const DielectricBsdf&) const { return 0.0f; }
  float operator()(const BlackBsdf&) const { return 0.0f; }
  float operator()(const NullBsdf&) const { return 0.0f; }
};

struct Sample {
  Vec3 n, wo;
  float u_lobe;
  Vec2 u;

  std::optional<BsdfSample> operator()(const DiffuseBsdf& b) const {
    const Vec3 side = face_forward(n, wo);
    const Vec3 local = sample_cosine_hemisphere(u);
    if (local.z <= 0.0f) return std::nullopt;
    const Vec3 wi = Frame::from_z(side).to_world(local);
    return BsdfSample{wi, b.reflectance, cosine_hemisphere_pdf(local.z), false};
  }
  // Chooses reflection with probability F, so the weight is 1 either way (no colour).
  std::optional<BsdfSample> operator()(const DielectricBsdf& b) const {
    const float cos_o = dot(n, wo);
    const float f = fresnel_dielectric(cos_o, b.ior);
    const Vec3 side = cos_o > 0.0f ? n : -n;
    if (u_lobe < f) return BsdfSample{reflect(wo, side), RGB(1.0f), f, true};
    const float eta = cos_o > 0.0f ? b.ior : 1.0f / b.ior;
    const auto wt = refract(wo, side, eta);
    if (!wt) return BsdfSample{reflect(wo, side), RGB(1.0f), 1.0f, true};
    // Radiance is scaled by 1/eta^2 crossing the interface (solid-angle compression).
    return BsdfSample{*wt, RGB(1.0f / sqr(eta)), 1.0f - f, true};
  }
  std::optional<BsdfSample> operator()(const BlackBsdf&) const { return std::nullopt; }
  std::optional<BsdfSample> operator()(const NullBsdf&) const {
    return BsdfSample{-wo, RGB(1.0f), 1.0f, true};
  }
};

struct IsSpecular {
  bool operator()(const DiffuseBsdf&) const { return false; }
  bool operator()(const BlackBsdf&) const { return false; }
  bool operator()(const DielectricBsdf&) const { return true; }
  bool operator()(const NullBsdf&) const { return true; }
};

struct Albedo {
  RGB operator()(const DiffuseBsdf& b) const { return b.reflectance; }
  RGB operator()(const DielectricBsdf&) const { return RGB(1.0f); }
  RGB operator()(const BlackBsdf&) const { return RGB(0.0f); }
  RGB operator()(const NullBsdf&) const { return RGB(0.0f); }
};

}  // namespace

RGB bsdf_eval(const Bsdf& bsdf, Vec3 n, Vec3 wo, Vec3 wi) { return std::visit(Eval{n, wo, wi}, bsdf); }
float bsdf_pdf(const Bsdf& bsdf, Vec3 n, Vec3 wo, Vec3 wi) { return std::visit(Pdf{n, wo, wi}, bsdf); }
std::optional<BsdfSample> bsdf_sample(const Bsdf& bsdf, Vec3 n, Vec3 wo, float u_lobe, Vec2 u) {
  return std::visit(Sample{n, wo, u_lobe, u}, bsdf);
}
bool is_specular(const Bsdf& bsdf) { return std::visit(IsSpecular{}, bsdf); }
RGB bsdf_albedo(const Bsdf& bsdf) { return std::visit(Albedo{}, bsdf); }

}  // namespace caligo
