// The files `caligo realtime` writes, as one OutputTransaction planned before the first frame:
// a folder of frames (frame_NNNN.png or .exr), a GIF, or the last frame as one PNG or EXR, and
// the reference comparison strip when asked for. Every output is checked first (exit 2 for a
// bad name or one that is an input of the scene, 3 for a folder that cannot be written); frames
// are staged as they are rendered and everything is renamed into place together at the end, so
// a full disk or a failed write replaces nothing. A frame folder that did not exist is created,
// and removed again when the run fails before its commit.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "core/output_transaction.h"
#include "image/image.h"
#include "image/tonemap.h"
#include "output_folder.h"

namespace caligo {

enum class RealtimeOutputKind { none, folder, gif, single_png, single_exr };
RealtimeOutputKind realtime_output_kind(const std::string& out);

class RealtimeOutputs {
 public:
  RealtimeOutputs(const RealtimeOptions& o, const SceneDesc& desc, int frames);
  ~RealtimeOutputs();
  RealtimeOutputs(const RealtimeOutputs&) = delete;
  RealtimeOutputs& operator=(const RealtimeOutputs&) = delete;

  // Whether frame() keeps a frame (every frame for a folder or GIF, else only the last).
  bool wants_frame(bool last) const {
    return kind_ == RealtimeOutputKind::folder || kind_ == RealtimeOutputKind::gif ||
           (last && kind_ != RealtimeOutputKind::none);
  }
  // Frame `index` as rendered: staged (a folder's frame, or the last frame as the one image)
  // or kept for the GIF.
  void frame(const Image& image, int index, bool last);
  // The comparison strip (realtime | reference | error), staged; its path for the message.
  void comparison(int width, int height, const std::vector<uint8_t>& rgb8);
  const std::string& comparison_path() const { return comparison_; }
  // Writes the GIF, then renames every output into place.
  void commit(int width, int height, float fps);

 private:
  RealtimeOutputKind kind_;
  PreviewSettings preview_;
  bool exr_frames_;
  std::string comparison_;
  std::optional<OutputFolder> folder_;
  std::optional<OutputTransaction> tx_;
  std::vector<std::vector<uint8_t>> gif_frames_;

};

}  // namespace caligo
