#include "checkpoint.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/checksum.h"
#include "scene/builtins.h"

namespace caligo {
namespace {

uint64_t fnv1a(uint64_t h, const std::string& bytes) {
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

// Floats in hexadecimal: exact, so equal settings always give equal text.
std::string hex(float v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%a", double(v));
  return buffer;
}

}  // namespace

std::string scene_source(const std::string& scene_argument) {
  if (const BuiltinScene* builtin = find_builtin(scene_argument)) return "builtin:" + builtin->json;
  std::ifstream in(scene_argument, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

uint64_t checkpoint_key(const std::string& scene_source, const std::vector<std::string>& files,
                        const RenderSettings& s, float time, const std::vector<std::string>& priorities) {
  std::ostringstream canon;
  canon << "files " << files.size();
  for (const std::string& f : files) {
    const FileChecksum sum = file_checksum(f);
    canon << ' ' << sum.bytes << ':' << sum.crc;
  }
  const PathSettings& p = s.path;
  canon << " v1 caligo " << CALIGO_VERSION << " res " << s.resolution.x << 'x' << s.resolution.y << " seed " << s.seed << " bounces "
        << p.limits.max_bounces << ' ' << p.limits.max_volume_bounces << " rr " << p.russian_roulette_depth
        << " null " << p.max_null_crossings << " dist " << int(p.distance_sampling) << " nee "
        << hex(p.volume_nee_scale) << " lights " << int(p.light_sampler) << " abs " << p.absorption_by_weight
        << " deferred " << p.deferred_nee << " secondary " << int(p.secondary) << " guiding " << int(p.guiding) << " filter " << int(s.filter.type) << ' ' << hex(s.filter.radius)
        << ' ' << hex(s.filter.sigma) << " crop " << hex(s.crop.x0) << ' ' << hex(s.crop.x1) << ' '
        << hex(s.crop.y0) << ' ' << hex(s.crop.y1) << " aovs " << s.aovs.bits() << " march "
        << hex(s.march.opacity_threshold) << ' ' << s.march.max_steps_per_span << ' '
        << hex(s.march.auto_step_fraction) << " time " << hex(time) << " adaptive " << hex(s.adaptive.threshold) << ' ' << s.adaptive.min_samples
        << " clamp " << hex(s.clamp.direct) << ' ' << hex(s.clamp.indirect) << " priorities";
  for (const std::string& pr : priorities) canon << ' ' << pr.size() << ':' << pr;
  return fnv1a(fnv1a(0xcbf29ce484222325ull, scene_source), canon.str());
}

std::optional<double> parse_duration(const std::string& text) {
  if (text.empty()) return std::nullopt;
  double scale = 1.0;
  std::string number = text;
  switch (text.back()) {
    case 's': number.pop_back(); break;
    case 'm': scale = 60.0; number.pop_back(); break;
    case 'h': scale = 3600.0; number.pop_back(); break;
    default: break;
  }
  if (number.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(number.c_str(), &end);
  if (end != number.c_str() + number.size() || !std::isfinite(v) || !(v > 0.0) || v * scale > 1e9)
    return std::nullopt;
  return v * scale;
}

}  // namespace caligo
