#include "render_outputs.h"

#include <filesystem>
#include <vector>

#include "core/error.h"
#include "image/exr_io.h"
#include "image/png_io.h"
#include "image/tonemap.h"

namespace caligo {

RenderOutputs::RenderOutputs(const RenderOptions& o) {
  if (o.output && o.output->empty()) throw InputError(kCommandLine, "-o: the output path is empty");
  exr_ = o.output ? *o.output : std::filesystem::path(o.scene).stem().string() + ".exr";
  if (std::filesystem::path(exr_).extension() != ".exr")
    throw InputError(SourceLocation{exr_, ""}, "output must be an .exr file");
  png_ = std::filesystem::path(exr_).replace_extension(".png").string();
  outputs_.add(exr_, "image");
  outputs_.add(png_, "preview");
  asked_checkpoint_ = o.checkpoint.has_value();
  checkpoint_ = o.checkpoint ? *o.checkpoint : exr_.substr(0, exr_.size() - 4) + ".ckpt";
  if (asked_checkpoint_) {
    outputs_.add(checkpoint_, "checkpoint");
    return;
  }
  // The interrupt's own checkpoint is checked now too.
  try {
    OutputTransaction probe = outputs_;
    probe.add(checkpoint_, "checkpoint");
    interrupt_checkpoint_ = true;
  } catch (const std::exception&) {
    interrupt_checkpoint_ = false;
  }
}

void RenderOutputs::write(const Image& image, const Film* film, uint64_t key, float exposure,
                          bool interrupted) const {
  std::vector<OutputTransaction::Writer> writers = {
      [&](const std::string& temp) { write_exr(temp, image); },
      [&](const std::string& temp) {
        write_png(temp, image.width(), image.height(), to_srgb8_preview(image, PreviewSettings{exposure, true}));
      }};
  OutputTransaction tx = outputs_;
  const bool interrupt_writes = interrupted && !asked_checkpoint_ && interrupt_checkpoint_;
  if (interrupt_writes) tx.add(checkpoint_, "checkpoint");
  if (asked_checkpoint_ || interrupt_writes) writers.push_back([&](const std::string& temp) { film->save(temp, key); });
  tx.commit(writers);
}

}  // namespace caligo
