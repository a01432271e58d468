// The entry points of caligo_oiio.so, the plugin that keeps OpenImageIO (~260 shared
// libraries, ~0.2–0.45 s and ~100 MB (docs/benchmarks.md) of process start-up) out of every run that reads no image
// and writes no GIF (see core/module_loader.h). Host and plugin are built together, so C++
// types cross the boundary; exceptions do not: failures come back as messages.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace caligo {

// A picture as OpenImageIO decodes it: channels interleaved, rows top to bottom, as floats.
struct OiioImage {
  int width = 0, height = 0, channels = 0;
  bool integer_format = false;  // stored as 8/16/32-bit integers (not half, float or double)
  std::string color_space;      // OpenImageIO's "oiio:ColorSpace" attribute
  std::vector<float> pixels;
};

enum class OiioReadStatus { kOk, kCannotOpen, kBadSize, kCannotRead };

struct OiioPluginApi {
  int abi_version;
  // Reads the first subimage. kBadSize (width, height, channels filled, nothing allocated)
  // when the size is not positive or exceeds `max_pixels`; other failures fill `error`.
  OiioReadStatus (*read_image)(const std::string& path, int64_t max_pixels, OiioImage* out, std::string* error);
  // Writes an animated GIF (one subimage per 8-bit RGB frame, looping forever) to `file`;
  // false and `error` on failure.
  bool (*write_gif)(const std::string& file, int width, int height, const std::vector<std::vector<uint8_t>>& frames,
                    float frames_per_second, std::string* error);
};

inline constexpr int kOiioPluginAbi = 1;
inline constexpr const char* kOiioPluginName = "caligo_oiio";
inline constexpr const char* kOiioPluginSymbol = "caligo_oiio_plugin";

// The plugin's table, loaded on first use; throws std::runtime_error when the plugin is
// missing or from another build. `purpose` completes that message.
const OiioPluginApi& oiio_plugin(const char* purpose);

}  // namespace caligo
