#include "distributed/share.h"

#include "core/enum_names.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace caligo::distributed {

Range share_of(int total, int first, int rank, int ranks) {
  if (total < 0 || ranks < 1 || rank < 0 || rank >= ranks)
    throw std::invalid_argument("share_of: bad range or rank (total " + std::to_string(total) + ", rank " +
                                std::to_string(rank) + " of " + std::to_string(ranks) + ")");
  const int base = total / ranks, extra = total % ranks;
  return {first + rank * base + std::min(rank, extra), base + (rank < extra ? 1 : 0)};
}

std::optional<Split> split_from_name(std::string_view name) {
  return enum_from_name(std::array<EnumName<Split>, 2>{{{Split::kSamples, "samples"}, {Split::kRows, "rows"}}}, name);
}

float row_fraction(int row, int height) {
  if (height < 1 || row < 0 || row > height) throw std::invalid_argument("row_fraction: row outside the image");
  // CropWindow::pixels takes ceil(double(height) * double(f)); the float nearest row / height
  // may land one row off, so step to the neighbouring floats until it does not (a row spans
  // 1 / height >= 2^-16, far more than a float's spacing below 1).
  const auto edge = [height](float f) { return int(std::ceil(double(height) * double(f))); };
  float f = float(double(row) / double(height));
  while (edge(f) > row) f = std::nextafter(f, 0.0f);
  while (edge(f) < row) f = std::nextafter(f, 1.0f);
  return f;
}

RenderSettings settings_for_rank(const RenderSettings& frame, Split split, int rank, int ranks) {
  RenderSettings s = frame;
  if (split == Split::kSamples) {
    const Range samples = share_of(frame.spp, frame.first_sample, rank, ranks);
    s.first_sample = samples.first;
    s.spp = samples.count;
    return s;
  }
  const PixelBounds bounds = frame.crop.pixels(frame.resolution);
  const Range rows = share_of(std::max(0, bounds.height()), bounds.min.y, rank, ranks);
  s.crop.y0 = row_fraction(rows.first, frame.resolution.y);
  s.crop.y1 = row_fraction(rows.first + rows.count, frame.resolution.y);
  return s;
}

}  // namespace caligo::distributed
