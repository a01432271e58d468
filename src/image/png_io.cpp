#include "image/png_io.h"

#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "core/atomic_file.h"
#include "image/oiio_plugin.h"

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

// libpng reports errors through a callback that must not return: it records the message and
// longjmps back to write_rows, which owns nothing that needs a destructor.
struct PngErrors {
  char message[256] = "";
};

void on_png_error(png_structp png, png_const_charp message) {
  auto* errors = static_cast<PngErrors*>(png_get_error_ptr(png));
  std::snprintf(errors->message, sizeof errors->message, "%s", message);
  png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}

// Returns an empty string on success, else libpng's message. Plain C control flow only:
// setjmp/longjmp must not skip C++ destructors.
std::string write_rows(std::FILE* file, int width, int height, const uint8_t* rgb8) {
  PngErrors errors;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &errors, on_png_error, on_png_warning);
  if (png == nullptr) return "out of memory";
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_write_struct(&png, nullptr);
    return "out of memory";
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return errors.message;
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < height; ++y) png_write_row(png, rgb8 + size_t(y) * size_t(width) * 3);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return "";
}

void write_png_now(const std::string& file, const std::string& path, int width, int height,
                   const std::vector<uint8_t>& rgb8) {
  std::FILE* out = std::fopen(file.c_str(), "wb");
  if (out == nullptr) throw std::runtime_error("cannot write PNG file " + path + ": cannot create " + file);
  std::string error = write_rows(out, width, height, rgb8.data());
  if (std::fclose(out) != 0 && error.empty()) error = "cannot finish writing " + file;
  if (!error.empty()) throw std::runtime_error("cannot write PNG file " + path + ": " + error);
}

void write_gif_now(const std::string& file, const std::string& path, int width, int height,
                   const std::vector<std::vector<uint8_t>>& frames, float fps) {
  std::string error;
  if (!oiio_plugin("needed to write GIF files").write_gif(file, width, height, frames, fps, &error))
    throw std::runtime_error("cannot write GIF file " + path + ": " + error);
  // The GIF writer does not report a failed write (a full disk): a whole file ends with the
  // trailer byte 0x3B.
  std::FILE* in = std::fopen(file.c_str(), "rb");
  const bool whole = in != nullptr && std::fseek(in, -1, SEEK_END) == 0 && std::fgetc(in) == 0x3B;
  if (in != nullptr) std::fclose(in);
  if (!whole) throw std::runtime_error("cannot write GIF file " + path + ": the file written is incomplete (is the disk full?)");
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

std::string encode_png(int width, int height, const std::vector<uint8_t>& rgb8) {
  check_buffer(width, height, rgb8);
  char* data = nullptr;
  size_t size = 0;
  std::FILE* out = ::open_memstream(&data, &size);
  if (out == nullptr) throw std::runtime_error("cannot encode a PNG: out of memory");
  const std::string error = write_rows(out, width, height, rgb8.data());
  std::fclose(out);  // sets data and size
  std::string bytes(data ? data : "", data ? size : 0);
  std::free(data);
  if (!error.empty()) throw std::runtime_error("cannot encode a PNG: " + error);
  return bytes;
}

void write_png(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb8) {
  check_buffer(width, height, rgb8);
  write_file_atomically(
      path, [&](const std::string& temp_path) { write_png_now(temp_path, path, width, height, rgb8); });
}

}  // namespace caligo
