// The procedural volumes. Each is a field: a world box, the grids it fills, a conservative
// test that lets whole 8^3 blocks be skipped (a distance bound on the undisplaced shape plus
// the largest displacement), and its values at a point. Blocks are filled in parallel, each
// from its own coordinates only, so the result does not depend on scheduling.
#include "grids/grid_generate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <variant>

#include "core/error.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "grids/grid_noise.h"

namespace caligo {
namespace {

constexpr int kMaxChannels = 3;
using Values = std::array<float, kMaxChannels>;

float saturate(float x) { return std::clamp(x, 0.0f, 1.0f); }

// Polynomial smooth minimum (blends within k); never above min(a, b) and 1-Lipschitz.
float smooth_min(float a, float b, float k) {
  const float h = std::max(k - std::abs(a - b), 0.0f) / k;
  return std::min(a, b) - h * h * k * 0.25f;
}

// |noise| <= 1.04; displacement bounds use this margin.
constexpr float kNoiseBound = 1.1f;
// Smaller values are set to 0 (inactive): far below anything visible, and they would only
// enlarge the active set.
constexpr float kDensityCutoff = 1e-3f;

class CloudField {
 public:
  explicit CloudField(uint64_t seed) : shape_(hash_values(seed, 1)), detail_(hash_values(seed, 2)) {
    Pcg32 rng(seed, 0xc10d);
    const auto uniform = [&](float lo, float hi) { return lo + (hi - lo) * rng.next_float(); };
    balls_.push_back({Vec3(uniform(-0.15f, 0.15f), 1.05f, uniform(-0.15f, 0.15f)), 0.85f});
    const float phase = uniform(0.0f, 2.0f * kPi);
    for (int i = 0; i < 5; ++i) {
      const float angle = phase + 2.0f * kPi * (float(i) + uniform(-0.2f, 0.2f)) / 5.0f;
      const float dist = uniform(0.6f, 0.95f);
      balls_.push_back(
          {Vec3(dist * std::cos(angle), uniform(0.8f, 1.05f), dist * std::sin(angle)), uniform(0.5f, 0.7f)});
    }
    for (int i = 0; i < 2; ++i)
      balls_.push_back(
          {Vec3(uniform(-0.4f, 0.4f), uniform(1.5f, 1.7f), uniform(-0.4f, 0.4f)), uniform(0.4f, 0.52f)});
    // Keep every ball, displaced, inside the box.
    const float margin = kDisplace * kNoiseBound + 0.05f;
    for (Ball& b : balls_) {
      const float horizontal = std::hypot(b.centre.x, b.centre.z);
      if (horizontal + b.radius > 2.0f - margin) b.radius = 2.0f - margin - horizontal;
      b.radius = std::min(b.radius, 2.5f - margin - b.centre.y);
    }
  }

  static Bounds3 bounds() { return {Vec3(-2.0f, 0.0f, -2.0f), Vec3(2.0f, 2.5f, 2.0f)}; }
  static std::vector<std::string> names() { return {"density"}; }
  static Values cutoffs() { return {kDensityCutoff, 0.0f, 0.0f}; }

  bool may_touch(Vec3 centre, float radius) const {
    return distance_bound(centre) <= radius + kDisplace * kNoiseBound;
  }

  Values evaluate(Vec3 p) const {
    const float d = distance_bound(p);
    if (d > kDisplace * kNoiseBound) return {};
    // Billows everywhere but on the base, which stays flat-ish as cumulus bases are.
    const float lift = smoothstep(kBase, kBase + 0.5f, p.y);
    const float displaced = d - kDisplace * lift * shape_.billow(p * 1.1f, 4);
    const float core = saturate(-displaced / kEdge);
    if (core <= 0.0f) return {};
    const float erosion = 0.5f + 0.5f * detail_.fbm(p * 5.5f, 3);
    return {saturate(core - 0.6f * (1.0f - core) * erosion), 0.0f, 0.0f};
  }

 private:
  struct Ball {
    Vec3 centre;
    float radius;
  };
  static constexpr float kDisplace = 0.28f;  // metres the billows push the surface out
  static constexpr float kEdge = 0.10f;      // metres over which density rises to 1
  static constexpr float kBase = 0.42f;      // height of the flat base

  // A lower bound of the distance to the undisplaced cloud (negative inside).
  float distance_bound(Vec3 p) const {
    float d = kInfinity;
    for (const Ball& b : balls_) d = smooth_min(d, distance(p, b.centre) - b.radius, 0.35f);
    return std::max(d, kBase - p.y);
  }

  std::vector<Ball> balls_;
  GradientNoise shape_, detail_;
};

class SmokeField {
 public:
  explicit SmokeField(uint64_t seed)
      : warp_{GradientNoise(hash_values(seed, 11)), GradientNoise(hash_values(seed, 12)),
              GradientNoise(hash_values(seed, 13))},
        sway_(hash_values(seed, 14)),
        turbulence_(hash_values(seed, 15)) {}

  static Bounds3 bounds() { return {Vec3(-1.25f, 0.0f, -1.25f), Vec3(1.25f, 4.0f, 1.25f)}; }
  static std::vector<std::string> names() { return {"density"}; }
  static Values cutoffs() { return {kDensityCutoff, 0.0f, 0.0f}; }

  bool may_touch(Vec3 centre, float radius) const {
    const float top = std::min(centre.y + radius, 4.0f);
    const float reach = plume_radius(top) * (1.0f + kWarp * kNoiseBound) + kSway * kNoiseBound;
    return std::hypot(centre.x, centre.z) - radius <= reach;
  }

  Values evaluate(Vec3 p) const {
    const float r = plume_radius(p.y);
    const Vec3 q = p * 1.6f;
    const Vec3 w = p + kWarp * r * Vec3(warp_[0](q), warp_[1](q), warp_[2](q));
    const float rw = plume_radius(w.y);
    const float sway = kSway * std::min(1.0f, w.y / 2.0f);
    const float ax = sway * sway_(Vec3(0.0f, w.y * 0.45f, 0.0f)),
                az = sway * sway_(Vec3(5.1f, w.y * 0.45f, 0.0f));
    const float radial = std::hypot(w.x - ax, w.z - az) / rw;
    if (radial >= 1.0f) return {};
    const float profile = sqr(1.0f - radial * radial);
    const float turbulence = 0.55f + 0.45f * turbulence_.fbm(p * 3.0f, 4);
    const float height =
        smoothstep(0.0f, 0.25f, p.y) * (1.0f - smoothstep(2.6f, 3.9f, p.y)) * (1.0f - 0.4f * p.y / 4.0f);
    return {saturate(1.2f * profile * turbulence * height), 0.0f, 0.0f};
  }

 private:
  static constexpr float kWarp = 0.3f;   // domain warp, relative to the plume's radius
  static constexpr float kSway = 0.25f;  // metres the axis wanders

  static float plume_radius(float y) { return 0.12f + 0.14f * std::clamp(y, 0.0f, 4.0f); }

  std::array<GradientNoise, 3> warp_;
  GradientNoise sway_, turbulence_;
};

class FireField {
 public:
  explicit FireField(uint64_t seed)
      : shape_(hash_values(seed, 21)),
        heat_(hash_values(seed, 22)),
        burn_(hash_values(seed, 23)),
        soot_(hash_values(seed, 24)) {}

  static Bounds3 bounds() { return {Vec3(-1.5f, 0.0f, -1.5f), Vec3(1.5f, 3.0f, 1.5f)}; }
  static std::vector<std::string> names() { return {"density", "temperature", "flame"}; }
  // Below 300 K nothing glows visibly; the cut keeps such voxels out of the active set.
  static Values cutoffs() { return {kDensityCutoff, 300.0f, kDensityCutoff}; }

  bool may_touch(Vec3 centre, float radius) const {
    // The upward stretch shortens distances by at most kStretch.
    const float s_lower =
        (kStretch * (distance(centre, kCentre) - radius) - kDisplace * kNoiseBound) / kRadius;
    return s_lower <= kOuter;
  }

  Values evaluate(Vec3 p) const {
    Vec3 v = p - kCentre;
    if (v.y > 0.0f) v.y *= kStretch;  // a rising ball is taller than wide
    const float s = (length(v) - kDisplace * shape_.fbm(p * 1.8f, 4)) / kRadius;  // 1 at the surface
    if (s > kOuter) return {};
    const float hot = 0.85f + 0.15f * heat_.fbm(p * 4.0f, 3);
    const float kelvin =
        s < 1.0f ? 900.0f + 2100.0f * std::pow(1.0f - s, 0.7f) : 900.0f * saturate((1.1f - s) / 0.1f);
    const float flame =
        saturate(1.0f - std::abs(s - 0.7f) / 0.3f) * saturate(0.55f + 0.45f * burn_.fbm(p * 5.0f, 3));
    const float shell = smoothstep(0.7f, 0.95f, s) * (1.0f - smoothstep(1.15f, kOuter, s));
    const float soot = shell * (0.45f + 0.55f * (0.5f + 0.5f * soot_.fbm(p * 3.5f, 4)));
    const float inner = 0.06f * saturate((1.0f - s) / 0.2f);
    return {saturate(std::max(soot, inner)), kelvin * hot, flame};
  }

 private:
  static constexpr Vec3 kCentre{0.0f, 1.35f, 0.0f};
  static constexpr float kRadius = 0.72f;
  static constexpr float kStretch = 0.8f;
  static constexpr float kDisplace = 0.2f;
  static constexpr float kOuter = 1.4f;  // normalised radius beyond which every channel is 0

  GradientNoise shape_, heat_, burn_, soot_;
};

using Field = std::variant<CloudField, SmokeField, FireField>;

Field make_field(const GenerateSettings& s) {
  switch (s.kind) {
    case GeneratedVolume::kCloud:
      return CloudField(s.seed);
    case GeneratedVolume::kSmoke:
      return SmokeField(s.seed);
    case GeneratedVolume::kFire:
      return FireField(s.seed);
  }
  throw std::logic_error("unknown generated volume");
}

template <typename F>
std::vector<SparseFloatGrid> sample_field(const F& field, int resolution) {
  const Bounds3 box = F::bounds();
  const std::vector<std::string> names = F::names();
  const Values cutoffs = F::cutoffs();
  const Vec3 extent = box.diagonal();
  const float voxel = max_component(extent) / float(resolution);
  std::array<int, 3> dims{}, blocks{};
  for (int a = 0; a < 3; ++a) {
    dims[a] = std::max(1, int(std::lround(extent[a] / voxel)));
    blocks[a] = (dims[a] + kBlockDim - 1) / kBlockDim;
  }
  const Vec3 origin = box.lo + Vec3(0.5f * voxel);  // centre of voxel (0, 0, 0)
  const float block_radius = 0.5f * std::sqrt(3.0f) * float(kBlockDim) * voxel;
  const int block_count = blocks[0] * blocks[1] * blocks[2];
  const size_t channels = names.size();
  // One pointer per block and channel, a block only where data is (a 2 KB slot each would need
  // gigabytes at resolution 1024).
  std::vector<std::unique_ptr<SparseBlock>> slots(size_t(block_count) * channels);
  parallel_for(block_count, [&](int b) {
    const std::array<int, 3> o{kBlockDim * (b % blocks[0]), kBlockDim * (b / blocks[0] % blocks[1]),
                               kBlockDim * (b / (blocks[0] * blocks[1]))};
    const Vec3 centre = origin + voxel * Vec3(float(o[0]) + 3.5f, float(o[1]) + 3.5f, float(o[2]) + 3.5f);
    if (!field.may_touch(centre, block_radius)) return;
    std::array<SparseBlock, kMaxChannels> out;
    std::array<bool, kMaxChannels> any{};
    for (size_t c = 0; c < channels; ++c) out[c] = SparseBlock{o, {}};
    for (int x = 0; x < kBlockDim; ++x)
      for (int y = 0; y < kBlockDim; ++y)
        for (int z = 0; z < kBlockDim; ++z) {
          if (o[0] + x >= dims[0] || o[1] + y >= dims[1] || o[2] + z >= dims[2]) continue;
          const Vec3 p = origin + voxel * Vec3(float(o[0] + x), float(o[1] + y), float(o[2] + z));
          const Values v = field.evaluate(p);
          for (size_t c = 0; c < channels; ++c) {
            if (v[c] < cutoffs[c]) continue;
            out[c].values[size_t(block_offset(x, y, z))] = v[c];
            any[c] = any[c] || v[c] != 0.0f;
          }
        }
    for (size_t c = 0; c < channels; ++c)
      if (any[c]) slots[size_t(b) * channels + c] = std::make_unique<SparseBlock>(out[c]);
  });
  std::vector<SparseFloatGrid> grids(channels);
  for (size_t c = 0; c < channels; ++c) {
    grids[c].name = names[c];
    grids[c].voxel_size = voxel;
    grids[c].origin = origin;
    for (int b = 0; b < block_count; ++b)
      if (const auto& slot = slots[size_t(b) * channels + c]) grids[c].blocks.push_back(*slot);
  }
  return grids;
}

}  // namespace

std::optional<GeneratedVolume> parse_generated_volume(const std::string& name) {
  if (name == "cloud") return GeneratedVolume::kCloud;
  if (name == "smoke") return GeneratedVolume::kSmoke;
  if (name == "fire") return GeneratedVolume::kFire;
  return std::nullopt;
}

Bounds3 generated_bounds(GeneratedVolume kind) {
  switch (kind) {
    case GeneratedVolume::kCloud:
      return CloudField::bounds();
    case GeneratedVolume::kSmoke:
      return SmokeField::bounds();
    case GeneratedVolume::kFire:
      return FireField::bounds();
  }
  return {};
}

std::vector<SparseFloatGrid> generate_grids(const GenerateSettings& settings) {
  if (settings.resolution < kMinGenerateResolution || settings.resolution > kMaxGenerateResolution)
    throw InputError("--res must be in [" + std::to_string(kMinGenerateResolution) + ", " +
                     std::to_string(kMaxGenerateResolution) + "], got " +
                     std::to_string(settings.resolution));
  return std::visit([&](const auto& field) { return sample_field(field, settings.resolution); },
                    make_field(settings));
}

}  // namespace caligo
