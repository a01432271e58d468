// The files `caligo render` writes, as one plan checked before any work: the beauty EXR, its PNG
// preview, and the checkpoint, which is the one --checkpoint names, or the one an interrupt
// writes beside the image when none was asked for (that one is dropped, and the interrupt
// message says so, when it cannot be written). Each write is one OutputTransaction: all of its
// files land, or none changes.
#pragma once

#include <cstdint>
#include <string>

#include "commands.h"
#include "core/output_transaction.h"
#include "image/image.h"
#include "render/film.h"

namespace caligo {

class RenderOutputs {
 public:
  // Throws InputError for an output that cannot be written (a bad -o is refused now, not after
  // the render).
  explicit RenderOutputs(const RenderOptions& o);

  const std::string& exr() const { return exr_; }
  const std::string& checkpoint() const { return checkpoint_; }
  // Whether an interrupted render leaves a checkpoint to resume.
  bool interrupt_leaves_checkpoint() const { return asked_checkpoint_ || interrupt_checkpoint_; }

  // The image and its preview, and the checkpoint of `film` when one was asked for, or when
  // `interrupted` and one can be written. `film` may be null only when no checkpoint is asked.
  void write(const Image& image, const Film* film, uint64_t key, float exposure, bool interrupted) const;

 private:
  std::string exr_, png_, checkpoint_;
  bool asked_checkpoint_ = false;
  bool interrupt_checkpoint_ = false;
  OutputTransaction outputs_;
};

}  // namespace caligo
