#include "settings/aov.h"

#include "core/error.h"

namespace caligo {

std::string_view aov_name(Aov a) {
  switch (a) {
    case Aov::kAlpha: return "alpha";
    case Aov::kDepth: return "depth";
    case Aov::kNormal: return "normal";
    case Aov::kAlbedo: return "albedo";
    case Aov::kSurfaceDirect:
    case Aov::kSurfaceIndirect:
    case Aov::kVolumeDirect:
    case Aov::kVolumeIndirect:
    case Aov::kSurfaceEmission:
    case Aov::kVolumeEmission:
    case Aov::kBackground: return light_kind_name(LightKind(int(a) - int(Aov::kSurfaceDirect)));
    case Aov::kVariance: return "variance";
    case Aov::kSamples: return "samples";
  }
  return "?";
}

AovSet AovSet::parse(std::string_view list) {
  AovSet set;
  size_t start = 0;
  while (start <= list.size()) {
    const size_t comma = std::min(list.find(',', start), list.size());
    std::string name(list.substr(start, comma - start));
    start = comma + 1;
    // "volume.direct" is accepted for "volume_direct" (the dotted form some pipelines use).
    for (char& c : name)
      if (c == '.') c = '_';
    if (name == "beauty") continue;
    if (name == "default") {
      set.bits_ |= defaults().bits_;
      continue;
    }
    if (name == "all") {
      set.bits_ |= all().bits_;
      continue;
    }
    if (name == "lights") {
      for (int k = 0; k < kLightKindCount; ++k) set = set.with(light_aov(LightKind(k)));
      continue;
    }
    bool known = false;
    for (int a = 0; a < kAovCount; ++a)
      if (aov_name(Aov(a)) == name) {
        set = set.with(Aov(a));
        known = true;
      }
    if (!known) {
      std::string names = "beauty, default, all, lights";
      for (int a = 0; a < kAovCount; ++a) names += ", " + std::string(aov_name(Aov(a)));
      throw InputError("--aov: unknown output '" + printable_for_message(name) + "' (expected a comma-separated list of: " +
                       names + ")");
    }
    if (comma == list.size()) break;
  }
  return set;
}

std::vector<std::string> aov_channels(AovSet set) {
  std::vector<std::string> names = {"R", "G", "B"};
  if (set.has(Aov::kAlpha)) names.push_back("A");
  if (set.has(Aov::kDepth)) names.push_back("Z");
  if (set.has(Aov::kNormal))
    for (const char* c : {"N.X", "N.Y", "N.Z"}) names.push_back(c);
  if (set.has(Aov::kAlbedo))
    for (const char* c : {"albedo.R", "albedo.G", "albedo.B"}) names.push_back(c);
  for (int k = 0; k < kLightKindCount; ++k) {
    const Aov a = light_aov(LightKind(k));
    if (!set.has(a)) continue;
    for (const char* c : {".R", ".G", ".B"}) names.push_back(std::string(aov_name(a)) + c);
  }
  if (set.has(Aov::kVariance))
    for (const char* c : {"variance.R", "variance.G", "variance.B"}) names.push_back(c);
  if (set.has(Aov::kSamples)) names.push_back("samples");
  return names;
}

}  // namespace caligo
