#include "render_outputs.h"

#include <filesystem>
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

std::vector<OutputTransaction::Writer> image_writers(const Image& image, float exposure) {
  return {[&image](const std::string& temp) { write_exr(temp, image); },
          [&image, exposure](const std::string& temp) {
            write_png(temp, image.width(), image.height(), to_srgb8_preview(image, PreviewSettings{exposure, true}));
          }};
}

}  // namespace

void protect_scene_inputs(OutputTransaction& outputs, const SceneDesc& desc) {
  if (desc.file.rfind("builtin:", 0) != 0) outputs.protect(desc.file, "scene file");
  for (const std::string& f : desc.files) outputs.protect(f, "file the scene \"" + desc.file + "\" reads,");
}

RenderOutputs::RenderOutputs(const RenderOptions& o, const SceneDesc& desc) {
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

void RenderOutputs::write_final(const Image& image, const Film* film, uint64_t key, float exposure) const {
  std::vector<OutputTransaction::Writer> writers = image_writers(image, exposure);
  if (!asked_checkpoint_) {
    OutputTransaction(final_).commit(writers);
    return;
  }
  writers.push_back([&](const std::string& temp) { film->save(temp, key); });
  try {
    OutputTransaction(final_).commit(writers);
  } catch (const EnvironmentError& e) {
    // Keep what fits: the image and preview alone, then report the checkpoint.
    OutputTransaction images;
    images.add(exr_, "image");
    images.add(png_, "preview");
    writers.pop_back();
    images.commit(writers);
    throw EnvironmentError(std::string(e.what()) + "; the image " + exr_ + " and its preview were written");
  }
}

void RenderOutputs::write_interrupted(const Image& image, const Film& film, uint64_t key, float exposure) const {
  std::vector<OutputTransaction::Writer> writers = image_writers(image, exposure);
  if (interrupt_leaves_checkpoint()) writers.push_back([&](const std::string& temp) { film.save(temp, key); });
  OutputTransaction(interrupted_).commit(writers);
}

}  // namespace caligo
