#include "render_outputs.h"

#include <filesystem>
#include <memory>
#include <vector>

#include "core/error.h"
#include "image/exr_io.h"
#include "image/png_io.h"
#include "image/tonemap.h"

namespace caligo {
namespace {

std::string with_suffix(const std::string& exr, const char* suffix) {
  return exr.substr(0, exr.size() - 4) + suffix;
}

std::vector<OutputTransaction::Writer> image_writers(const Image& image, const PreviewSettings& preview,
                                                     const ExrAttributes& attributes, const Image& shown) {
  return {[&image, &attributes](const std::string& temp) { write_exr(temp, image, false, attributes); },
          [&shown, preview](const std::string& temp) {
            write_png(temp, shown.width(), shown.height(), to_srgb8_preview(shown, preview));
          }};
}

}  // namespace

void protect_scene_inputs(OutputTransaction& outputs, const SceneDesc& desc) {
  if (desc.file.rfind("builtin:", 0) != 0) outputs.protect(desc.file, "scene file");
  for (const std::string& f : desc.files) outputs.protect(f, "file the scene \"" + desc.file + "\" reads,");
}

RenderOutputs::RenderOutputs(const RenderOptions& o, const SceneDesc& desc)
    : preview_{o.exposure, o.view == "filmic"} {
  if (o.output && o.output->empty()) throw InputError(kCommandLine, "-o: the output path is empty");
  exr_ = o.output ? *o.output : std::filesystem::path(o.scene).stem().string() + ".exr";
  if (std::filesystem::path(exr_).extension() != ".exr")
    throw InputError(SourceLocation{exr_, ""}, "output must be an .exr file");
  png_ = with_suffix(exr_, ".png");
  partial_exr_ = with_suffix(exr_, ".partial.exr");
  partial_png_ = with_suffix(exr_, ".partial.png");
  asked_checkpoint_ = o.checkpoint.has_value();
  checkpoint_ = o.checkpoint ? *o.checkpoint : with_suffix(exr_, ".ckpt");
  for (OutputTransaction* plan : {&final_, &interrupted_}) {
    protect_scene_inputs(*plan, desc);
    if (o.resume) plan->protect(*o.resume, "checkpoint resumed", checkpoint_);
  }
  final_.add(exr_, "image");
  final_.add(png_, "preview");
  interrupted_.add(partial_exr_, "partial image");
  interrupted_.add(partial_png_, "partial preview");
  final_images_ = std::make_unique<OutputTransaction>(final_);
  interrupted_images_ = std::make_unique<OutputTransaction>(interrupted_);
  if (asked_checkpoint_) {
    final_.add(checkpoint_, "checkpoint");
    interrupted_.add(checkpoint_, "checkpoint");
    return;
  }
  // The interrupt's own checkpoint is checked now too; without it an interrupt writes the image.
  try {
    OutputTransaction probe = interrupted_;
    probe.add(checkpoint_, "checkpoint");
    interrupted_.add(checkpoint_, "checkpoint");
    interrupt_checkpoint_ = true;
  } catch (const std::exception&) {
    interrupt_checkpoint_ = false;
  }
}

// Commits `plan` (images, then a checkpoint when `film`); when that fails, the images alone
// (their own plan), then reports the checkpoint: what fits is kept.
void RenderOutputs::write_keeping_images(const OutputTransaction& plan, const OutputTransaction& images_only,
                                         const Image& image, const Film* film, uint64_t key,
                                         const ExrAttributes& attributes, const Image* preview) const {
  std::vector<OutputTransaction::Writer> writers = image_writers(image, preview_, attributes, preview ? *preview : image);
  if (!film) {
    OutputTransaction(plan).commit(writers);
    return;
  }
  writers.push_back([&](const std::string& temp) { film->save(temp, key); });
  try {
    OutputTransaction(plan).commit(writers);
  } catch (const EnvironmentError& e) {
    writers.pop_back();
    OutputTransaction(images_only).commit(writers);
    throw EnvironmentError(std::string(e.what()) + "; the image " + images_only.path(0) + " and its preview were written");
  }
}

void RenderOutputs::write_final(const Image& image, const Film* film, uint64_t key, const ExrAttributes& attributes,
                                const Image* preview) const {
  write_keeping_images(final_, *final_images_, image, asked_checkpoint_ ? film : nullptr, key, attributes, preview);
}

void RenderOutputs::write_interrupted_images(const Image& image, const ExrAttributes& attributes,
                                             const Image* preview) const {
  write_keeping_images(*interrupted_images_, *interrupted_images_, image, nullptr, 0, attributes, preview);
}

void RenderOutputs::write_interrupted(const Image& image, const Film& film, uint64_t key,
                                      const ExrAttributes& attributes) const {
  write_keeping_images(interrupted_, *interrupted_images_, image, interrupt_leaves_checkpoint() ? &film : nullptr, key,
                       attributes);
}

}  // namespace caligo
