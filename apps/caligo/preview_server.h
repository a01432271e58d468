// caligo render --preview / caligo realtime --preview: a page on 127.0.0.1 that shows the image as
// each pass (or frame) lands, with an exposure slider, a layer picker (the AOVs and light
// layers), a denoised/noisy toggle, samples per pixel, the ETA, the real-time pass table, and a
// stop button that stops the render as Ctrl-C does.
//
// Security: bound to the loopback interface only; every request must carry the random token
// printed with the URL (?token=...), or it is refused with 403; requests are bounded in size
// (a few KiB); nothing is served from disk: images are encoded from memory, so no file outside
// the render's outputs (or inside them) can be read through it. httplib (Debian's
// libcpp-httplib-dev) serves on its own threads, in the plugin caligo_preview.so
// (preview_plugin.h: preview_server.cpp is its only translation unit with httplib), loaded
// only by runs with --preview.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "image/image.h"

namespace caligo {

struct PreviewState {
  Image image;                // the film resolved: beauty and layers (and "denoised" when there is one)
  int done = 0, target = 0;   // samples per pixel (frames for realtime)
  double seconds = 0;
  bool finished = false;
  std::string table;          // realtime: the per-pass table, plain text
};

class PreviewServer {
 public:
  // Binds 127.0.0.1:`port` (0: a free port). `on_stop` runs when the page's stop button is
  // pressed. Throws EnvironmentError when the port cannot be bound or the plugin is missing.
  PreviewServer(int port, std::function<void()> on_stop, bool filmic);
  ~PreviewServer();
  PreviewServer(const PreviewServer&) = delete;
  PreviewServer& operator=(const PreviewServer&) = delete;

  // http://127.0.0.1:PORT/?token=TOKEN
  std::string url() const;
  // A new state for the page (between passes, on the render's own thread).
  void publish(PreviewState state);
  // Waits up to `seconds` for a page that is open to fetch the last state's image (so that
  // it shows the final one before the command exits); returns at once when no page is open.
  void linger(double seconds);

 private:
  void* server_;  // the plugin's
  std::string url_;
};

// --preview [PORT] of a command line: nullptr without it; otherwise a server listening (the
// URL printed on stderr). PORT must be an integer in [0, 65535] (0 or none: any free port).
std::unique_ptr<PreviewServer> start_preview(const std::optional<std::string>& port, std::function<void()> on_stop,
                                             bool filmic);

// The page's image of `layer` ("beauty", "denoised", a layer prefix such as "albedo", "N" for
// normals, "Z" for depth, "A" for alpha) as an RGB image, or nullopt when the image lacks it.
std::optional<Image> preview_layer(const Image& image, const std::string& layer);
// The layers preview_layer can show for `image`, beauty first.
std::vector<std::string> preview_layers(const Image& image);

}  // namespace caligo
