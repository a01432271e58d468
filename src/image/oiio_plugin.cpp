// caligo_oiio.so: the only code that calls OpenImageIO (image_read.cpp and png_io.cpp reach it
// through oiio_plugin.h).
#include "image/oiio_plugin.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <system_error>

namespace caligo {
namespace {

bool is_integer_format(OIIO::TypeDesc format) {
  return format.basetype != OIIO::TypeDesc::FLOAT && format.basetype != OIIO::TypeDesc::HALF &&
         format.basetype != OIIO::TypeDesc::DOUBLE;
}

// No image format Caligo reads packs pixels tighter than deflate's limit of about 1032:1
// (PNG, EXR's ZIP; JPEG's and RLE's limits are lower), so a header claiming more packed bytes
// than that ratio allows from the file's length is a lie, refused before any buffer is made.
constexpr double kMaxCompressionRatio = 1032.0;

bool size_is_plausible(const OIIO::ImageSpec& spec, const std::string& path) {
  std::error_code ec;
  const uintmax_t file_bytes = std::filesystem::file_size(path, ec);
  if (ec) return true;  // not a plain file: the reader's own checks decide
  // The least the file can have packed: one bit per pixel (1-bit masks are common gobos, and a
  // palette index expands into three or four channels).
  const double packed = double(spec.width) * double(spec.height) / 8.0;
  return packed <= kMaxCompressionRatio * double(file_bytes) + 4096.0;
}

OiioReadStatus read_image(const std::string& path, int64_t max_pixels, OiioImage* out, std::string* error) {
  std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path);
  if (!in) {
    *error = OIIO::geterror();
    return OiioReadStatus::kCannotOpen;
  }
  const OIIO::ImageSpec spec = in->spec();
  out->width = spec.width;
  out->height = spec.height;
  out->channels = spec.nchannels;
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || int64_t(spec.width) * spec.height > max_pixels)
    return OiioReadStatus::kBadSize;
  if (!size_is_plausible(spec, path)) {
    *error = "its header claims " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + " pixels, more "
             "than the file's " + std::to_string(std::filesystem::file_size(path)) + " bytes can hold (truncated or corrupt)";
    return OiioReadStatus::kCannotRead;
  }
  out->integer_format = is_integer_format(spec.format);
  out->color_space = spec.get_string_attribute("oiio:ColorSpace");
  // Only what is used: R, G, B, or the grey of one or two (grey + alpha) channels.
  out->channels = spec.nchannels >= 3 ? 3 : 1;
  out->pixels.resize(size_t(spec.width) * size_t(spec.height) * size_t(out->channels));
  if (!in->read_image(0, 0, 0, out->channels, OIIO::TypeDesc::FLOAT, out->pixels.data())) {
    *error = in->geterror();
    return OiioReadStatus::kCannotRead;
  }
  in->close();
  return OiioReadStatus::kOk;
}

bool write_gif(const std::string& file, int width, int height, const std::vector<std::vector<uint8_t>>& frames,
               float fps, std::string* error) {
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create("gif");
  if (!out) {
    *error = OIIO::geterror();
    return false;
  }
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
  if (!ok) *error = out->geterror();
  return ok;
}

}  // namespace
}  // namespace caligo

extern "C" __attribute__((visibility("default"))) const caligo::OiioPluginApi* caligo_oiio_plugin() {
  static const caligo::OiioPluginApi api{caligo::kOiioPluginAbi, &caligo::read_image, &caligo::write_gif};
  return &api;
}
