#include "scene/volume_parser.h"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "scene/transform_parser.h"

namespace caligo {
namespace {

// Henyey-Greenstein style asymmetry: |g| = 1 is a delta distribution, which no phase
// function here can represent or sample.
const Range kAsymmetry = Range::open(-1, 1);

PhaseFunction parse_phase(const JsonCursor& c) {
  ObjectReader r(c, "a phase function");
  const std::string type = r.choice("type", {"isotropic", "hg", "schlick", "double_hg"});
  r.set_what("a " + type + " phase function");
  PhaseFunction phase;
  if (type == "isotropic") {
    r.allow({"type"});
  } else if (type == "hg") {
    r.allow({"type", "g"});
    phase = HenyeyGreensteinPhase{r.number("g", kAsymmetry)};
  } else if (type == "schlick") {
    r.allow({"type", "g", "k"});
    const auto [which, value] = r.exactly_one("g", "k");
    const float x = value.number(kAsymmetry);
    phase = which == 0 ? SchlickPhase::from_g(x) : SchlickPhase{x};
  } else {
    r.allow({"type", "g1", "g2", "w"});
    phase = DoubleHenyeyGreensteinPhase{r.number("g1", kAsymmetry), r.number("g2", kAsymmetry),
                                        r.number("w", Range::closed(0, 1))};
  }
  r.finish();
  return phase;
}

// Lattice cells per metre: beyond these the pattern is finer than a float position resolves
// over a scene, or coarser than any scene.
const Range kNoiseScale = Range::closed(1e-6, 1e6);

NoiseModulation parse_noise(const JsonCursor& c) {
  ObjectReader r(c, "a density noise");
  r.allow({"scale", "amplitude", "wind"});
  NoiseModulation n;
  n.scale = r.number_or("scale", n.scale, kNoiseScale);
  n.amplitude = r.number_or("amplitude", n.amplitude, Range::closed(0, 1));
  if (auto w = r.optional_vec3("wind")) n.wind = *w;
  r.finish();
  return n;
}

VolumeShader parse_medium(const JsonCursor& c) {
  ObjectReader r(c, "a medium");
  r.allow({"sigma_a", "sigma_s", "emission", "density", "phase", "falloff", "noise", "step_size"});
  VolumeShader s;
  s.sigma_a = r.rgb_or("sigma_a", RGB(0.0f));
  s.sigma_s = r.rgb_or("sigma_s", RGB(0.0f));
  s.emission = r.rgb_or("emission", RGB(0.0f));
  s.density = r.number_or("density", 1.0f, Range::non_negative());
  if (auto p = r.optional("phase")) s.phase = parse_phase(*p);
  if (auto f = r.optional("falloff")) {
    ObjectReader fr(*f, "a density falloff");
    fr.allow({"exponent"});
    s.field = RadialFalloffDensity{fr.number_or("exponent", 1.0f, Range::positive())};
    fr.finish();
  }
  if (auto n = r.optional("noise")) s.noise = parse_noise(*n);
  s.step_size = r.number_or("step_size", 0.0f, Range::positive());
  r.finish();
  return s;
}

const VolumeShader& find_medium(const JsonCursor& c, const std::vector<NamedMedium>& media) {
  std::vector<std::string> names;
  for (const NamedMedium& m : media) names.push_back(m.name);
  return media[find_definition(c, names, "medium", "media")].shader;
}

VolumeShape parse_volume_shape(ObjectReader& r, const std::string& type, const Transform& placement) {
  if (type == "sphere") {
    const Vec3 center = r.vec3("center");
    return SphereVolumeShape{Sphere::make(center, r.number("radius", size_range()), placement)};
  }
  const BoxCorners box = read_box_corners(r);
  return BoxVolumeShape{placement, box.min, box.max};
}

}  // namespace

std::vector<NamedMedium> parse_media(const JsonCursor& c) {
  std::vector<NamedMedium> media;
  for (const auto& [name, m] : named_definitions(c, "medium", "media"))
    media.push_back({name, parse_medium(m)});
  return media;
}

VolumePrimitive parse_volume(const JsonCursor& c, const std::vector<NamedMedium>& media) {
  ObjectReader r(c, "a volume");
  const std::string type = r.choice("type", {"sphere", "box"});
  r.set_what("a " + type + " volume");
  if (type == "sphere")
    r.allow({"type", "center", "radius", "medium", "transform"});
  else
    r.allow({"type", "min", "max", "medium", "transform"});
  Transform placement;
  if (auto t = r.optional("transform")) placement = parse_transform(*t);
  VolumePrimitive v{parse_volume_shape(r, type, placement), find_medium(r.required("medium"), media)};
  r.finish();
  return v;
}

}  // namespace caligo
