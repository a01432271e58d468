#include "image/exr_io.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <half.h>

#include <algorithm>
#include <filesystem>
#include <system_error>
#include <cstdint>
#include <stdexcept>
#include <tuple>

#include "core/atomic_file.h"
#include "core/error.h"
#include "image/exr_header_attributes.h"

namespace caligo {

namespace {

// Slices point straight into interleaved samples (the Image's own, or a HALF copy of them), so
// OpenEXR reads and writes the layout in place. Its Slice holds a non-const pointer whichever
// way the data flows; read_exr_now passes its own, freshly allocated image, which readPixels fills.
Imf::FrameBuffer frame_buffer(const Image& layout, Imf::PixelType type, const void* samples,
                              size_t sample_size, const Imath::Box2i& data_window) {
  const size_t x_stride = sample_size * size_t(layout.channel_count());
  const size_t y_stride = x_stride * size_t(layout.width());
  Imf::FrameBuffer buffer;
  for (int c = 0; c < layout.channel_count(); ++c) {
    const char* first = static_cast<const char*>(samples) + sample_size * size_t(c);
    Imf::Slice slice = Imf::Slice::Make(type, first, data_window, x_stride, y_stride);
    buffer.insert(layout.channels()[size_t(c)], slice);
  }
  return buffer;
}

Imf::Header exr_header(const Image& image, bool half, const ExrAttributes& attributes) {
  Imf::Header header(image.width(), image.height());
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const std::string& name : image.channels()) {
    header.channels().insert(name, Imf::Channel(half ? Imf::HALF : Imf::FLOAT));
  }
  add_attributes(header, attributes);
  return header;
}

void write_exr_now(const std::string& file, const Image& image, bool half, const Imf::Header& header) {
  const Imath::Box2i& window = header.dataWindow();
  Imf::OutputFile out(file.c_str(), header);
  // Unlike InputFile, OutputFile does not convert FLOAT to HALF: hand it rounded copies.
  std::vector<Imath::half> halves;
  if (half) {
    halves.assign(image.pixels().begin(), image.pixels().end());
    out.setFrameBuffer(frame_buffer(image, Imf::HALF, halves.data(), sizeof(Imath::half), window));
  } else {
    out.setFrameBuffer(frame_buffer(image, Imf::FLOAT, image.pixels().data(), sizeof(float), window));
  }
  out.writePixels(image.height());
}  // closing the file here flushes it before write_file_atomically renames it

// Sort key: root layer first, then layers by name; within a layer R, G, B, A, then the rest.
std::tuple<bool, std::string, int, std::string> order_key(const std::string& name) {
  size_t dot = name.rfind('.');
  bool in_layer = dot != std::string::npos;
  std::string layer = in_layer ? name.substr(0, dot) : "";
  std::string channel = in_layer ? name.substr(dot + 1) : name;
  static const std::string rgba[] = {"R", "G", "B", "A"};
  int rank = int(std::find(std::begin(rgba), std::end(rgba), channel) - std::begin(rgba));
  return {in_layer, layer, rank, channel};
}

std::vector<std::string> channel_names(const Imf::ChannelList& channels) {
  std::vector<std::string> names;
  for (auto it = channels.begin(); it != channels.end(); ++it) {
    if (it.channel().xSampling != 1 || it.channel().ySampling != 1) {
      throw InputError("channel \"" + std::string(it.name()) + "\" is subsampled, which Caligo cannot read");
    }
    names.push_back(it.name());
  }
  return names;
}

// Guards against a corrupt header asking for an absurd allocation (2^31 floats = 8 GiB).
constexpr int64_t kMaxSamples = int64_t(1) << 31;

// No OpenEXR compression packs more than deflate's ~1032:1 (ZIP; RLE, PIZ, B44 and DWA pack
// less), so a header claiming more half-float samples than that from the file's length lies.
constexpr double kMaxCompressionRatio = 1032.0;

Image allocate_for(const Imf::Header& header, uint64_t file_bytes) {
  const Imath::Box2i& window = header.dataWindow();
  int64_t width = int64_t(window.max.x) - window.min.x + 1;
  int64_t height = int64_t(window.max.y) - window.min.y + 1;
  std::vector<std::string> names = channel_names(header.channels());
  int64_t channels = std::max<int64_t>(int64_t(names.size()), 1);
  if (width < 1 || height < 1 || width > kMaxSamples / height / channels) {
    throw InputError("implausible data window of " + std::to_string(width) + "x" + std::to_string(height) +
                     " pixels");
  }
  if (double(width) * double(height) * double(channels) * 2.0 > kMaxCompressionRatio * double(file_bytes) + 65536.0)
    throw InputError("its header claims " + std::to_string(width) + "x" + std::to_string(height) + " pixels of " +
                     std::to_string(channels) + " channels, more than the file's " + std::to_string(file_bytes) +
                     " bytes can hold (truncated or corrupt)");
  return Image(int(width), int(height), exr_channel_order(std::move(names)));
}

Image read_exr_now(const std::string& path) {
  Imf::InputFile in(path.c_str());
  std::error_code ec;
  const uintmax_t bytes = std::filesystem::file_size(path, ec);
  Image image = allocate_for(in.header(), ec ? UINT64_MAX / 2048 : uint64_t(bytes));
  const Imath::Box2i& window = in.header().dataWindow();
  in.setFrameBuffer(frame_buffer(image, Imf::FLOAT, image.pixels().data(), sizeof(float), window));
  in.readPixels(window.min.y, window.max.y);
  return image;
}

}  // namespace

std::vector<std::string> exr_channel_order(std::vector<std::string> names) {
  std::sort(names.begin(), names.end(),
            [](const std::string& a, const std::string& b) { return order_key(a) < order_key(b); });
  return names;
}

void write_exr(const std::string& path, const Image& image, bool half, const ExrAttributes& attributes) {
  if (image.pixel_count() == 0) {
    throw std::invalid_argument("write_exr: " + path + ": an EXR file cannot hold an empty image");
  }
  const Imf::Header header = exr_header(image, half, attributes);  // a bad attribute is a bug, not an I/O error
  write_file_atomically(path, [&](const std::string& temp_path) {
    try {
      write_exr_now(temp_path, image, half, header);
    } catch (const std::exception& e) {
      throw std::runtime_error("cannot write OpenEXR file " + path + ": " + e.what());
    }
  });
}

Image read_exr(const std::string& path) {
  try {
    return read_exr_now(path);
  } catch (const std::exception& e) {
    // Iex exceptions (missing file, bad magic number, truncated data), std::bad_alloc and
    // our own checks above, which do not know the path.
    throw InputError(SourceLocation{path, ""}, std::string("cannot read OpenEXR file: ") + e.what());
  }
}

ExrAttributes read_exr_attributes(const std::string& path) {
  try {
    Imf::InputFile in(path.c_str());
    return attributes_of(in.header());
  } catch (const std::exception& e) {
    throw InputError(SourceLocation{path, ""}, std::string("cannot read OpenEXR file: ") + e.what());
  }
}

}  // namespace caligo
