// The files `caligo render` writes, as plans checked before any work: the beauty EXR, its PNG
// preview and the asked-for checkpoint when the render finishes; the partial image and preview
// (NAME.partial.exr/.png, so an earlier finished NAME.exr survives) and a checkpoint, the asked-
// for one or one beside the image, when it is interrupted. No output may be a file the render
// reads (the scene file, its meshes, grids, images and profiles, the checkpoint resumed; only the
// checkpoint output may be the resumed one). Each write is one OutputTransaction: all of its
// files land, or none changes; a final checkpoint that does not fit does not cost the image.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "commands.h"
#include "core/output_transaction.h"
#include "image/exr_attributes.h"
#include "image/image.h"
#include "image/tonemap.h"
#include "render/film.h"

namespace caligo {

// Protects every file `desc` was read from (its scene file unless built in, and
// SceneDesc::files) in `outputs`.
void protect_scene_inputs(OutputTransaction& outputs, const SceneDesc& desc);

class RenderOutputs {
 public:
  // Throws InputError for an output that cannot be written or would replace an input (a bad -o
  // is refused now, not after the render).
  RenderOutputs(const RenderOptions& o, const SceneDesc& desc);

  const std::string& exr() const { return exr_; }
  const std::string& partial_exr() const { return partial_exr_; }
  const std::string& checkpoint() const { return checkpoint_; }
  // Whether an interrupted render leaves a checkpoint to resume.
  bool interrupt_leaves_checkpoint() const { return asked_checkpoint_ || interrupt_checkpoint_; }

  // The finished image (with `attributes` in its header), its preview and the asked-for
  // checkpoint of `film`; when only the checkpoint fails, the image and preview are written and
  // the EnvironmentError says so.
  // `preview`, when given, is what the PNG shows instead of the image's beauty (the denoised one).
  void write_final(const Image& image, const Film* film, uint64_t key, const ExrAttributes& attributes,
                   const Image* preview = nullptr) const;
  // The partial image and preview, and a checkpoint when one can be written; the images are
  // kept when only the checkpoint fails, as above.
  void write_interrupted(const Image& image, const Film& film, uint64_t key, const ExrAttributes& attributes) const;
  // The partial image and preview alone, no checkpoint (a film that cannot be resumed, as the
  // two halves of --denoise).
  void write_interrupted_images(const Image& image, const ExrAttributes& attributes, const Image* preview) const;

 private:
  void write_keeping_images(const OutputTransaction& plan, const OutputTransaction& images_only, const Image& image,
                            const Film* film, uint64_t key, const ExrAttributes& attributes,
                            const Image* preview = nullptr) const;

  PreviewSettings preview_;  // --exposure and --view
  std::string exr_, png_, partial_exr_, partial_png_, checkpoint_;
  bool asked_checkpoint_ = false;
  bool interrupt_checkpoint_ = false;
  OutputTransaction final_, interrupted_;
  // The same plans without the checkpoint: what is written when only the checkpoint fails.
  std::unique_ptr<OutputTransaction> final_images_, interrupted_images_;
};

}  // namespace caligo
