#include "image/png_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <memory>
#include <stdexcept>

#include "core/atomic_file.h"

namespace caligo {

namespace {

void check_buffer(int width, int height, const std::vector<uint8_t>& rgb8) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("write_png: bad size " + std::to_string(width) + "x" +
                                std::to_string(height));
  }
  if (rgb8.size() != size_t(width) * size_t(height) * 3) {
    throw std::invalid_argument("write_png: " + std::to_string(rgb8.size()) + " bytes for a " +
                                std::to_string(width) + "x" + std::to_string(height) + " RGB image");
  }
}

void write_png_now(const std::string& file, const std::string& path, int width, int height,
                   const std::vector<uint8_t>& rgb8) {
  // Ask for the PNG codec by name rather than by the file's extension: the temporary name keeps
  // ".png" today, but write_png must write a PNG whatever the names look like.
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create("png");
  if (!out) throw std::runtime_error("cannot write PNG file " + path + ": " + OIIO::geterror());
  OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
  bool ok = out->open(file, spec) && out->write_image(OIIO::TypeDesc::UINT8, rgb8.data()) && out->close();
  if (!ok) throw std::runtime_error("cannot write PNG file " + path + ": " + out->geterror());
}

void write_gif_now(const std::string& file, const std::string& path, int width, int height,
                   const std::vector<std::vector<uint8_t>>& frames, float fps) {
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create("gif");
  if (!out) throw std::runtime_error("cannot write GIF file " + path + ": " + OIIO::geterror());
  OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
  const int rate[2] = {std::max(1, int(fps + 0.5f)), 1};
  spec.attribute("FramesPerSecond", OIIO::TypeRational, rate);
  spec.attribute("gif:LoopCount", 0);  // loop forever
  const std::vector<OIIO::ImageSpec> specs(frames.size(), spec);
  bool ok = out->open(file, int(specs.size()), specs.data());
  for (size_t i = 0; ok && i < frames.size(); ++i) {
    if (i > 0) ok = out->open(file, spec, OIIO::ImageOutput::AppendSubimage);
    ok = ok && out->write_image(OIIO::TypeDesc::UINT8, frames[i].data());
  }
  ok = ok && out->close();
  if (!ok) throw std::runtime_error("cannot write GIF file " + path + ": " + out->geterror());
}

}  // namespace

void write_gif(const std::string& path, int width, int height, const std::vector<std::vector<uint8_t>>& frames,
               float frames_per_second) {
  if (frames.empty()) throw std::invalid_argument("write_gif: no frames");
  for (const auto& f : frames) check_buffer(width, height, f);
  write_file_atomically(path, [&](const std::string& temp_path) {
    write_gif_now(temp_path, path, width, height, frames, frames_per_second);
  });
}

void write_png(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb8) {
  check_buffer(width, height, rgb8);
  write_file_atomically(
      path, [&](const std::string& temp_path) { write_png_now(temp_path, path, width, height, rgb8); });
}

}  // namespace caligo
