// Which samples train the guiding field and which field each sample uses: training iteration k
// renders samples [2^k - 1, 2^(k+1) - 1) of every pixel (1, 2, 4, ... per pixel, Mueller et al.'s
// doubling) with the field that k completed iterations left; after GuidingConfig::iterations
// iterations the field no longer changes. The schedule is a function of the sample index alone,
// so a render split into passes anywhere, resumed or spread over ranks uses the same field for
// the same sample. Every sample counts in the image: the early ones are noisier, never biased.
#pragma once

namespace caligo {

// The first sample after training iteration k (k < 30).
constexpr int training_iteration_end(int k) { return (2 << k) - 1; }

}  // namespace caligo
