// Scrambled, shuffled Sobol' samples (Burley 2020, "Practical Hash-based Owen Scrambling").
//
// Pipeline for one request (seed, pixel, dimension, sample index i):
//   1. i' = nested_uniform_scramble(i, shuffle seed)  -- a per-(pixel, dimension) permutation of
//      the sample indices that maps every aligned block of 2^m indices onto another aligned block,
//      so the first 2^m samples of a pixel are still a (0, m, 2)-net after the shuffle;
//   2. x = sobol_dim0(i'), y = sobol_dim1(i')       -- the first two Sobol' dimensions;
//   3. each coordinate is Owen-scrambled with its own seed, which keeps the net property and
//      makes pixels and dimensions statistically independent.
// Deviation from the paper: we use only the first two Sobol' dimensions ("padded" 2D samples,
// one independent pair per named dimension) rather than higher Sobol' dimensions.
// Thread safety: everything here is a pure function.
#include "core/sampler.h"

#include <algorithm>
#include <array>

#include "core/math.h"
#include "core/rng.h"

namespace caligo {
namespace {

uint32_t reverse_bits(uint32_t v) {
  v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
  v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
  v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
  return __builtin_bswap32(v);  // GCC and Clang; reverses the byte order in one instruction
}

// A hash in which output bit k depends only on input bits 0..k: adding a constant, multiplying by
// an odd number and xoring with a multiple by an even number all carry information only upwards.
// Applied to bit-reversed values this is a nested (Owen) permutation: each digit of the fraction
// is flipped by a hash of the digits before it (Laine & Karras 2011; constants from Burley 2020).
uint32_t laine_karras_permutation(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

// Generator matrix columns of the second Sobol' dimension (primitive polynomial x + 1, all
// direction numbers 1): column k is column k-1 xor itself shifted right by one, i.e. the
// upper-triangular Pascal matrix mod 2.
constexpr std::array<uint32_t, 32> kSobolDim1Columns = [] {
  std::array<uint32_t, 32> c{};
  uint32_t v = 1u << 31;
  for (uint32_t& col : c) {
    col = v;
    v ^= v >> 1;
  }
  return c;
}();

// The matrix-vector product over GF(2) one index byte at a time: entry b of table k is the xor of
// the columns selected by the bits of b, placed at byte k. Shuffled indices have random high bits,
// so a bit-by-bit loop would run all 32 steps with unpredictable branches (4 KiB, stays in L1).
constexpr auto kSobolDim1ByteTables = [] {
  std::array<std::array<uint32_t, 256>, 4> t{};
  for (size_t k = 0; k < 4; ++k)
    for (uint32_t b = 0; b < 256; ++b)
      for (size_t bit = 0; bit < 8; ++bit)
        if (b >> bit & 1u) t[k][b] ^= kSobolDim1Columns[8 * k + bit];
  return t;
}();

float to_unit_float(uint32_t bits) { return std::min(float(bits) * 0x1p-32f, kOneMinusEpsilon); }

// The three seeds of one (seed, pixel, dimension): the shuffle takes the low half of the hash, the two
// scrambles the halves of a second, unrelated mix of it. Pixel coordinates are packed into one word
// and hashed once per Sampler, so a request costs two mixes.
struct DimensionSeeds {
  uint32_t shuffle, scramble_x, scramble_y;
};

DimensionSeeds dimension_seeds(uint64_t pixel_key, uint32_t dimension) {
  const uint64_t base = hash_combine(pixel_key, dimension);
  const uint64_t scramble = mix_bits(base ^ 0x5343524d424c45ULL);  // any constant: decorrelates from base
  return {uint32_t(base), uint32_t(scramble), uint32_t(scramble >> 32)};
}

}  // namespace

uint32_t sobol_dim0(uint32_t index) { return reverse_bits(index); }

uint32_t sobol_dim1(uint32_t index) {
  const auto& t = kSobolDim1ByteTables;
  return t[0][index & 0xffu] ^ t[1][index >> 8 & 0xffu] ^ t[2][index >> 16 & 0xffu] ^ t[3][index >> 24];
}

uint32_t nested_uniform_scramble(uint32_t x, uint32_t seed) {
  return reverse_bits(laine_karras_permutation(reverse_bits(x), seed));
}

Sampler::Sampler(uint64_t seed, Vec2i pixel, uint32_t sample_index)
    : pixel_key_(hash_values(seed, uint64_t(uint32_t(pixel.x)) | uint64_t(uint32_t(pixel.y)) << 32)),
      pixel_(pixel),
      index_(sample_index) {}

uint64_t Sampler::stream_key(uint32_t dimension) const {
  return mix_bits(hash_combine(hash_combine(pixel_key_, dimension), uint64_t(index_) ^ 0x7472616b6bULL));
}

float Sampler::get_1d(uint32_t dimension) const {
  const DimensionSeeds seeds = dimension_seeds(pixel_key_, dimension);
  const uint32_t i = nested_uniform_scramble(index_, seeds.shuffle);
  // nested_uniform_scramble(sobol_dim0(i)) with the two bit reversals that cancel removed.
  return to_unit_float(reverse_bits(laine_karras_permutation(i, seeds.scramble_x)));
}

Vec2 Sampler::get_2d(uint32_t dimension) const {
  const DimensionSeeds seeds = dimension_seeds(pixel_key_, dimension);
  const uint32_t i = nested_uniform_scramble(index_, seeds.shuffle);
  return {to_unit_float(reverse_bits(laine_karras_permutation(i, seeds.scramble_x))),
          to_unit_float(nested_uniform_scramble(sobol_dim1(i), seeds.scramble_y))};
}

}  // namespace caligo
