// How one frame is split over the processes (ranks) of an MPI job. Pure functions, no MPI: the
// parts each rank renders, which merged (Film::merge, exact) give the frame of one process.
//   samples (default): every rank renders every pixel of the crop window, samples
//     [first + ..., ...) of its own contiguous range; costs balance whatever the image holds.
//   rows: every rank renders all samples of its own band of pixel rows of the crop window (a
//     crop window of its own); bands of sky and of smoke cost differently, so this balances
//     worse, but each rank touches fewer pixels (useful when a film is large and spp small).
// Either way each pixel gets each of its samples exactly once, from the same sampler
// (seed, pixel, sample index), so the merged film equals the single-process one bit for bit.
#pragma once

#include <optional>
#include <string_view>

#include "settings/render_settings.h"

namespace caligo::distributed {

// A contiguous range [first, first + count).
struct Range {
  int first = 0;
  int count = 0;
  friend bool operator==(const Range&, const Range&) = default;
};

// Rank `rank`'s part of [first, first + total) among `ranks`: the parts are contiguous and in
// rank order, cover the range exactly once, and their sizes differ by at most one (the first
// total % ranks ranks get one more). Ranks beyond `total` get an empty range. Throws
// std::invalid_argument for total < 0, ranks < 1 or rank outside [0, ranks).
Range share_of(int total, int first, int rank, int ranks);

enum class Split { kSamples, kRows };

// "samples" or "rows"; nullopt for anything else.
std::optional<Split> split_from_name(std::string_view name);

// A float f with ceil(height * f) == row (CropWindow::pixels' rule), for 0 <= row <=
// height: crop windows at these fractions hold exactly the rows between them.
float row_fraction(int row, int height);

// The settings rank `rank` of `ranks` renders for `frame`: its sample range of every pixel
// (kSamples) or every sample of its rows of the crop window (kRows; an empty crop when it has
// none). Resolution, outputs, seed and everything else stay the frame's.
RenderSettings settings_for_rank(const RenderSettings& frame, Split split, int rank, int ranks);

}  // namespace caligo::distributed
