#include "render_metadata.h"

#include <ctime>

namespace caligo {
namespace {

// OpenEXR's capDate ("YYYY:MM:DD hh:mm:ss", local time) and utcOffset (UTC = local + offset).
void add_capture_date(ExrAttributes& out) {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  if (!localtime_r(&now, &local)) return;
  char text[32];
  if (std::strftime(text, sizeof text, "%Y:%m:%d %H:%M:%S", &local) == 0) return;
  out.push_back({"capDate", std::string(text)});
  out.push_back({"utcOffset", float(-local.tm_gmtoff)});
}

}  // namespace

std::string software_name() { return std::string("Caligo ") + CALIGO_VERSION; }

ExrAttributes render_attributes(const RenderRecord& record, const Camera& camera) {
  ExrAttributes out = {
      {"software", software_name()},
      {"caligo/scene", record.scene},
      // Text: a seed is 64 bits, an EXR int 32.
      {"caligo/seed", std::to_string(record.seed)},
      {"caligo/samples", record.samples.first},
      {"caligo/samplesMax", record.samples.second},
      {"caligo/renderTime", float(record.seconds)},
      {"worldToCamera", camera.world_to_view()},
      {"worldToNDC", camera.view_to_ndc() * camera.world_to_view()},
  };
  add_capture_date(out);
  return out;
}

}  // namespace caligo
