// caligo_oiio.so: the only code that calls OpenImageIO (image_read.cpp and png_io.cpp reach it
// through oiio_plugin.h).
#include "image/oiio_plugin.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <memory>

namespace caligo {
namespace {

bool is_integer_format(OIIO::TypeDesc format) {
  return format.basetype != OIIO::TypeDesc::FLOAT && format.basetype != OIIO::TypeDesc::HALF &&
         format.basetype != OIIO::TypeDesc::DOUBLE;
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
  out->integer_format = is_integer_format(spec.format);
  out->color_space = spec.get_string_attribute("oiio:ColorSpace");
  out->pixels.resize(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, out->pixels.data())) {
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
