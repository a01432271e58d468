// The `many-lamps` built-in: a town at night in fog, generated in code. Three parallel
// streets (along -z, at x = -30, 0, 30) lined with boxes for buildings; 1,000 small lights:
// 126 street lamps (spots 5 m up, pointing down) and 874 windows on the street-facing facades
// (points and outward spots, 25 cm in front of the wall); thin haze (mean free path ~45 m)
// over everything and a faint night sky. The camera stands in the middle street. Light
// choice matters here: from any point only a few dozen lamps are near, and the spots light
// only what is under them (the light tree's benchmark, bench/bench_light_tree.cpp).
#include "scene/builtin_many_lamps.h"

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace caligo {
namespace {

constexpr int kLights = 1000;
constexpr float kStreets[] = {-30.0f, 0.0f, 30.0f};
constexpr int kBlocksPerRow = 14;
constexpr float kBlockPitch = 13.0f, kBlockLength = 10.0f;

// A small deterministic generator (the scene must be the same in every build).
struct Lcg {
  uint64_t state;
  float next() {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return float(state >> 40) * 0x1p-24f;
  }
};

std::string num(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", double(v));
  return buf;
}

std::string vec(float x, float y, float z) { return std::string("[") + num(x) + ", " + num(y) + ", " + num(z) + "]"; }

struct Building {
  float x0, x1, z0, z1, height;
  float facade_x, facing;  // the street-facing wall and its outward normal's x sign
};

std::vector<Building> buildings(Lcg& rng) {
  std::vector<Building> out;
  for (float street : kStreets)
    for (float side : {-1.0f, 1.0f})
      for (int k = 0; k < kBlocksPerRow; ++k) {
        const float near = street + side * 8.0f, far = street + side * 14.0f;
        const float z1 = -float(k) * kBlockPitch, z0 = z1 - kBlockLength;
        out.push_back({std::min(near, far), std::max(near, far), z0, z1, 6.0f + 14.0f * rng.next(), near, -side});
      }
  return out;
}

std::string street_lamps(Lcg& rng, int* count) {
  std::string json;
  for (size_t s = 0; s < std::size(kStreets); ++s)
    for (float side : {-1.0f, 1.0f})
      for (int k = 0; k < 21; ++k) {
        const float x = kStreets[s] + side * 5.5f, z = 2.0f - 9.0f * float(k) - 4.5f * (side > 0 ? 1.0f : 0.0f);
        const bool sodium = s != 1;
        json += std::string(",\n    {\"type\": \"spot\", \"position\": ") + vec(x, 5.0f, z) +
                ", \"look_at\": " + vec(x - side * 1.5f, 0.0f, z) +
                ", \"inner_angle\": 35, \"outer_angle\": 55, \"color\": " +
                (sodium ? vec(1.0f, 0.65f, 0.3f) : vec(0.85f, 0.92f, 1.0f)) +
                ", \"intensity\": " + num(40.0f + 20.0f * rng.next()) + "}";
        ++*count;
      }
  return json;
}

std::string windows(Lcg& rng, const std::vector<Building>& blocks, int count) {
  std::string json;
  for (int i = count; i < kLights; ++i) {
    const Building& b = blocks[size_t(rng.next() * float(blocks.size())) % blocks.size()];
    const float x = b.facade_x + b.facing * 0.25f;
    const float y = 1.5f + (b.height - 2.0f) * rng.next();
    const float z = b.z0 + 0.5f + (kBlockLength - 1.0f) * rng.next();
    const std::string color = vec(1.0f, 0.55f + 0.3f * rng.next(), 0.2f + 0.3f * rng.next());
    const float intensity = 0.5f + 2.0f * rng.next();
    if (i % 3 == 0) {
      json += std::string(",\n    {\"type\": \"spot\", \"position\": ") + vec(x, y, z) + ", \"direction\": " + vec(b.facing, -0.3f, 0.0f) +
              ", \"inner_angle\": 50, \"outer_angle\": 75, \"color\": " + color +
              ", \"intensity\": " + num(2.0f * intensity) + "}";
    } else {
      json += std::string(",\n    {\"type\": \"point\", \"position\": ") + vec(x, y, z) + ", \"color\": " + color +
              ", \"intensity\": " + num(intensity) + "}";
    }
  }
  return json;
}

}  // namespace

std::string many_lamps_scene() {
  Lcg rng{20261130};
  const std::vector<Building> blocks = buildings(rng);
  std::string json = R"json({
  "camera": {"position": [1.5, 2.2, 10], "look_at": [-0.5, 5, -80], "fov": 55, "resolution": [320, 180]},
  "render": {"spp": 16, "max_bounces": 4, "max_volume_bounces": 4},
  "materials": {
    "asphalt": {"type": "diffuse", "reflectance": 0.15},
    "concrete": {"type": "diffuse", "reflectance": [0.5, 0.47, 0.42]}
  },
  "media": {"haze": {"sigma_s": 0.02, "sigma_a": 0.002, "phase": {"type": "hg", "g": 0.6}}},
  "volumes": [{"type": "box", "min": [-50, 0, -200], "max": [50, 40, 20], "medium": "haze"}],
  "shapes": [
    {"type": "rectangle", "corner": [-50, 0, 20], "edge1": [100, 0, 0], "edge2": [0, 0, -220], "material": "asphalt"})json";
  for (const Building& b : blocks)
    json += std::string(",\n    {\"type\": \"box\", \"min\": ") + vec(b.x0, 0.0f, b.z0) + ", \"max\": " + vec(b.x1, b.height, b.z1) +
            ", \"material\": \"concrete\"}";
  json += R"json(
  ],
  "lights": [
    {"type": "environment", "color": [0.35, 0.45, 1], "radiance": 0.004})json";
  int count = 0;
  json += street_lamps(rng, &count);
  json += windows(rng, blocks, count);
  json += "\n  ]\n}\n";
  return json;
}

}  // namespace caligo
