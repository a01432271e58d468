#include "realtime_outputs.h"

#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "image/exr_io.h"
#include "image/png_io.h"
#include "image/tonemap.h"
#include "render_metadata.h"
#include "render_outputs.h"

namespace caligo {
namespace {

namespace fs = std::filesystem;

std::string frame_name(const std::string& folder, int index, bool exr) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d.%s", index, exr ? "exr" : "png");
  return (fs::path(folder) / name).string();
}

}  // namespace

RealtimeOutputKind realtime_output_kind(const std::string& out) {
  if (out.empty()) return RealtimeOutputKind::none;
  const std::string ext = fs::path(out).extension().string();
  if (ext == ".gif") return RealtimeOutputKind::gif;
  if (ext == ".png") return RealtimeOutputKind::single_png;
  if (ext == ".exr") return RealtimeOutputKind::single_exr;
  return RealtimeOutputKind::folder;
}

RealtimeOutputs::RealtimeOutputs(const RealtimeOptions& o, const SceneDesc& desc, int frames)
    : kind_(realtime_output_kind(o.output)), preview_{o.exposure, o.view == "filmic"}, exr_frames_(o.exr) {
  if (kind_ == RealtimeOutputKind::folder) folder_.emplace(o.output);
  tx_.emplace();
  protect_scene_inputs(*tx_, desc);
  try {
    if (kind_ == RealtimeOutputKind::folder)
      for (int i = 0; i < frames; ++i) tx_->add(frame_name(o.output, i, exr_frames_), "frame");
    else if (kind_ != RealtimeOutputKind::none)
      tx_->add(o.output, kind_ == RealtimeOutputKind::gif ? "GIF" : "image");
    if (o.compare_reference) {
      fs::path png = o.output.empty() ? fs::path("realtime") : fs::path(o.output);
      if (kind_ == RealtimeOutputKind::folder) png /= "comparison.png";
      else png.replace_extension(".comparison.png");
      comparison_ = png.string();
      tx_->add(comparison_, "comparison");
    }
  } catch (...) {
    tx_.reset();
    folder_.reset();
    throw;
  }
}

RealtimeOutputs::~RealtimeOutputs() {
  tx_.reset();  // removes what was staged, then the folder if this run made it
  folder_.reset();
}

void RealtimeOutputs::frame(const Image& image, int index, bool last) {
  const auto png = [&](const std::string& temp) {
    write_png(temp, image.width(), image.height(), to_srgb8_preview(image, preview_));
  };
  const ExrAttributes attributes = {{"software", software_name()}};
  const auto exr = [&](const std::string& temp) { write_exr(temp, image, false, attributes); };
  switch (kind_) {
    case RealtimeOutputKind::folder:
      if (exr_frames_) tx_->stage(size_t(index), exr);
      else tx_->stage(size_t(index), png);
      break;
    case RealtimeOutputKind::gif: gif_frames_.push_back(to_srgb8_preview(image, preview_)); break;
    case RealtimeOutputKind::single_png:
      if (last) tx_->stage(0, png);
      break;
    case RealtimeOutputKind::single_exr:
      if (last) tx_->stage(0, exr);
      break;
    case RealtimeOutputKind::none: break;
  }
}

void RealtimeOutputs::comparison(int width, int height, const std::vector<uint8_t>& rgb8) {
  tx_->stage(tx_->size() - 1, [&](const std::string& temp) { write_png(temp, width, height, rgb8); });
}

void RealtimeOutputs::commit(int width, int height, float fps) {
  if (kind_ == RealtimeOutputKind::gif)
    tx_->stage(0, [&](const std::string& temp) { write_gif(temp, width, height, gif_frames_, fps); });
  tx_->commit();
  if (folder_) folder_->keep();
}

}  // namespace caligo
