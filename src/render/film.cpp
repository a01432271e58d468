#include "render/film.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <utility>

#include "core/atomic_file.h"
#include "core/checksum.h"
#include "core/error.h"

namespace caligo {

Film::Film(Vec2i resolution, AovSet aovs)
    : resolution_(resolution), aovs_(aovs) {
  if (resolution.x <= 0 || resolution.y <= 0) throw std::invalid_argument("film resolution must be positive");
  light_.fill(-1);
  if (aovs.has(Aov::kAlpha)) alpha_ = std::exchange(channels_, channels_ + 1);
  if (aovs.has(Aov::kNormal)) normal_ = std::exchange(channels_, channels_ + 3);
  if (aovs.has(Aov::kAlbedo)) albedo_ = std::exchange(channels_, channels_ + 3);
  for (int k = 0; k < kLightKindCount; ++k)
    if (aovs.has(light_aov(LightKind(k)))) light_[size_t(k)] = std::exchange(channels_, channels_ + 3);
  if (aovs.has(Aov::kVariance)) squares_ = std::exchange(channels_, channels_ + 3);
  const size_t pixels = size_t(resolution.x) * size_t(resolution.y);
  sums_.resize(pixels * size_t(channels_));
  counts_.resize(pixels);
  if (aovs.has(Aov::kDepth)) depth_.assign(pixels, kInfinity);
}

void Film::add(int x, int y, const PathSample& s, float depth) {
  const size_t i = index(x, y);
  FixedSum* sum = &sums_[i * size_t(channels_)];
  ++counts_[i];
  const auto add3 = [&](int offset, float a, float b, float c) {
    sum[offset].add(a);
    sum[offset + 1].add(b);
    sum[offset + 2].add(c);
  };
  const RGB beauty = s.beauty();
  if (beauty.is_finite()) {
    add3(0, beauty.r, beauty.g, beauty.b);
    if (squares_ >= 0) add3(squares_, beauty.r * beauty.r, beauty.g * beauty.g, beauty.b * beauty.b);
    for (int k = 0; k < kLightKindCount; ++k)
      if (light_[size_t(k)] >= 0) add3(light_[size_t(k)], s.light[size_t(k)].r, s.light[size_t(k)].g, s.light[size_t(k)].b);
  }
  if (alpha_ >= 0 && std::isfinite(s.alpha)) sum[alpha_].add(s.alpha);
  if (normal_ >= 0 && is_finite(s.normal)) add3(normal_, s.normal.x, s.normal.y, s.normal.z);
  if (albedo_ >= 0 && s.albedo.is_finite()) add3(albedo_, s.albedo.r, s.albedo.g, s.albedo.b);
  if (!depth_.empty()) depth_[i] = std::min(depth_[i], depth);
}

Image Film::resolve() const {
  Image image(resolution_.x, resolution_.y, aov_channels(aovs_));
  // Channel order of the image (aov_channels): beauty, A, Z, normal, albedo, light layers; the
  // summed channels are in the same order with Z left out.
  const int z_channel = aovs_.has(Aov::kDepth) ? (alpha_ >= 0 ? 4 : 3) : -1;
  for (int y = 0; y < resolution_.y; ++y)
    for (int x = 0; x < resolution_.x; ++x) {
      const size_t i = index(x, y);
      const FixedSum* sum = &sums_[i * size_t(channels_)];
      const double inv = counts_[i] > 0 ? 1.0 / double(counts_[i]) : 0.0;
      int out = 0;
      for (int c = 0; c < channels_; ++c) {
        if (out == z_channel) image.at(x, y, out++) = depth_[i];
        if (c >= squares_ && squares_ >= 0) {
          // The variance of the mean from the two sums (zero below two samples).
          const double n = double(counts_[i]), mean = sum[c - squares_].value() * inv;
          const double var = n > 1.0 ? std::max(0.0, sum[c].value() * inv - mean * mean) / (n - 1.0) : 0.0;
          image.at(x, y, out++) = float(var);
          continue;
        }
        image.at(x, y, out++) = float(sum[c].value() * inv);
      }
      if (out == z_channel) image.at(x, y, out++) = depth_[i];
      if (aovs_.has(Aov::kSamples)) image.at(x, y, out++) = float(counts_[i]);
    }
  return image;
}

double Film::relative_error(int x, int y) const {
  const size_t i = index(x, y);
  if (squares_ < 0 || counts_[i] < 2) return kInfinity;
  const FixedSum* sum = &sums_[i * size_t(channels_)];
  const double n = double(counts_[i]);
  double variance = 0.0, mean = 0.0;
  for (int c = 0; c < 3; ++c) {
    const double m = sum[c].value() / n;
    mean += m / 3.0;
    variance += std::max(0.0, sum[squares_ + c].value() / n - m * m) / (n - 1.0) / 3.0;
  }
  return std::sqrt(variance) / std::max(mean, kRelativeErrorFloor);
}

std::optional<double> Film::estimated_rmse() const {
  if (squares_ < 0) return std::nullopt;
  double total = 0.0;
  uint64_t pixels = 0;
  for (size_t i = 0; i < counts_.size(); ++i) {
    if (counts_[i] < 2) continue;
    const FixedSum* sum = &sums_[i * size_t(channels_)];
    const double n = double(counts_[i]);
    for (int c = 0; c < 3; ++c) {
      const double mean = sum[c].value() / n;
      total += std::max(0.0, sum[squares_ + c].value() / n - mean * mean) / (n - 1.0);
    }
    ++pixels;
  }
  if (pixels == 0) return std::nullopt;
  return std::sqrt(total / (3.0 * double(pixels)));
}

void Film::merge(const Film& other) {
  if (other.resolution_ != resolution_ || other.aovs_ != aovs_)
    throw std::invalid_argument("films of different resolution or outputs cannot be merged");
  for (size_t i = 0; i < sums_.size(); ++i) sums_[i].add(other.sums_[i]);
  for (size_t i = 0; i < counts_.size(); ++i) counts_[i] += other.counts_[i];
  for (size_t i = 0; i < depth_.size(); ++i) depth_[i] = std::min(depth_[i], other.depth_[i]);
}

namespace {

// The raw film file: a fixed header, then counts (u32 per pixel), depths (f32 per pixel, when the
// film holds depth) and sums (16-byte little-endian integers, channels per pixel), in the host's
// byte order (x86-64 and aarch64 alike: little-endian), then the training state (Film::training_state,
// header.training_bytes long: a guided render's field), then the CRC-32 of everything before it
// (u32; core/checksum.h). The size must match the header exactly and the CRC the bytes: a
// flipped bit in a sum, a count or the header is refused, not resumed into a wrong image.
constexpr char kMagic[12] = {'C', 'A', 'L', 'I', 'G', 'O', '-', 'F', 'I', 'L', 'M', '\n'};
constexpr uint32_t kVersion = 3;  // 2: without the training state, 1: without the CRC
constexpr uint64_t kMaxTrainingBytes = uint64_t(1) << 30;
constexpr uint32_t kMaxSide = 1u << 16;
constexpr uint64_t kMaxFilmPixels = uint64_t(1) << 26;  // the render command's pixel cap
constexpr uint32_t kMaxFilmSamples = 1'000'000;         // the --spp maximum

struct FilmHeader {
  char magic[12];
  uint32_t version;
  uint32_t width, height;
  uint32_t aov_bits;
  uint64_t key;
  uint64_t training_bytes;  // Film::training_state, after the sums
};

// Sums per pixel for a set of outputs (the constructor's layout).
int summed_channels(AovSet aovs) {
  int n = 3 + (aovs.has(Aov::kAlpha) ? 1 : 0) + (aovs.has(Aov::kNormal) ? 3 : 0) + (aovs.has(Aov::kAlbedo) ? 3 : 0) +
          (aovs.has(Aov::kVariance) ? 3 : 0);
  for (int k = 0; k < kLightKindCount; ++k) n += aovs.has(light_aov(LightKind(k))) ? 3 : 0;
  return n;
}

// The header of a raw film of `total` bytes whose first bytes are `prefix`: magic, version, a
// resolution within the render limits, known outputs, and exactly the size they need. Nothing of
// the claimed size is allocated before this passes.
FilmHeader check_header(std::string_view prefix, uint64_t total, const SourceLocation& where) {
  FilmHeader header{};
  if (prefix.size() < sizeof header) throw InputError(where, "not a Caligo film (too short)");
  std::memcpy(&header, prefix.data(), sizeof header);
  if (std::memcmp(header.magic, kMagic, sizeof kMagic) != 0) throw InputError(where, "not a Caligo film");
  if (header.version != kVersion)
    throw InputError(where, "film version " + std::to_string(header.version) + ", expected " +
                                std::to_string(kVersion));
  const uint64_t pixels = uint64_t(header.width) * uint64_t(header.height);
  if (header.width == 0 || header.height == 0 || header.width > kMaxSide || header.height > kMaxSide ||
      pixels > kMaxFilmPixels)
    throw InputError(where, "film resolution " + std::to_string(header.width) + "x" + std::to_string(header.height) +
                                " is out of range");
  if (header.aov_bits >> kAovCount) throw InputError(where, "film names unknown outputs");
  const AovSet aovs = AovSet::from_bits(header.aov_bits);
  if (header.training_bytes > kMaxTrainingBytes) throw InputError(where, "film names a training state too large");
  const uint64_t expected = sizeof header + header.training_bytes +
                            pixels * (sizeof(uint32_t) + (aovs.has(Aov::kDepth) ? sizeof(float) : 0) +
                                      uint64_t(summed_channels(aovs)) * sizeof(FixedSum)) +
                            sizeof(uint32_t);
  if (total != expected)
    throw InputError(where, "film is " + std::to_string(total) + " bytes, its header needs " +
                                std::to_string(expected) + " (truncated or corrupt)");
  return header;
}

}  // namespace

uint64_t Film::memory_estimate(Vec2i resolution, AovSet aovs) {
  const uint64_t pixels = uint64_t(std::max(0, resolution.x)) * uint64_t(std::max(0, resolution.y));
  const uint64_t film = pixels * (uint64_t(summed_channels(aovs)) * sizeof(FixedSum) + sizeof(uint32_t) +
                                  (aovs.has(Aov::kDepth) ? sizeof(float) : 0));
  // The resolved image, and the EXR writer's copy of it.
  return film + 2 * pixels * aov_channels(aovs).size() * sizeof(float);
}

void Film::save(const std::string& path, uint64_t key) const {
  static_assert(sizeof(FixedSum) == 16);
  const std::string bytes = to_bytes(key);
  write_file_atomically(path, [&](const std::string& temp) {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot create " + temp);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    out.close();  // the close flushes: a full disk shows here
    if (!out) throw std::runtime_error("cannot write the film (is the disk full?)");
  });
}

Film Film::load(const std::string& path, uint64_t* key) {
  const SourceLocation where{path, ""};
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw InputError(where, "cannot open the film file");
  const uint64_t size = uint64_t(in.tellg());
  in.seekg(0);
  // The header says how big the file must be: checked before anything of that size is allocated.
  std::string bytes(std::min<uint64_t>(size, sizeof(FilmHeader)), '\0');
  if (!in.read(bytes.data(), std::streamsize(bytes.size()))) throw InputError(where, "cannot read the film file");
  check_header(bytes, size, where);
  bytes.resize(size);
  if (!in.read(bytes.data() + sizeof(FilmHeader), std::streamsize(size - sizeof(FilmHeader))))
    throw InputError(where, "cannot read the film file");
  return from_bytes(bytes, path, key);
}

std::string Film::to_bytes(uint64_t key) const {
  FilmHeader header{};
  std::memcpy(header.magic, kMagic, sizeof kMagic);
  header.version = kVersion;
  header.width = uint32_t(resolution_.x);
  header.height = uint32_t(resolution_.y);
  header.aov_bits = aovs_.bits();
  header.key = key;
  header.training_bytes = training_.size();
  const size_t counts = counts_.size() * sizeof(uint32_t), depths = depth_.size() * sizeof(float),
               sums = sums_.size() * sizeof(FixedSum);
  const size_t body = sizeof header + counts + depths + sums + training_.size();
  std::string bytes(body + sizeof(uint32_t), '\0');
  char* out = bytes.data();
  std::memcpy(out, &header, sizeof header);
  std::memcpy(out += sizeof header, counts_.data(), counts);
  if (depths > 0) std::memcpy(out + counts, depth_.data(), depths);  // no depth: data() may be null
  std::memcpy(out + counts + depths, sums_.data(), sums);
  if (!training_.empty()) std::memcpy(out + counts + depths + sums, training_.data(), training_.size());
  const uint32_t crc = crc32_of({bytes.data(), body});
  std::memcpy(bytes.data() + body, &crc, sizeof crc);
  return bytes;
}

Film Film::from_bytes(std::string_view bytes, const std::string& source, uint64_t* key) {
  const SourceLocation where{source, ""};
  const FilmHeader header = check_header(bytes, bytes.size(), where);
  const size_t body = bytes.size() - sizeof(uint32_t);
  uint32_t crc = 0;
  std::memcpy(&crc, bytes.data() + body, sizeof crc);
  if (crc != crc32_of(bytes.substr(0, body)))
    throw InputError(where, "the film's checksum does not match its contents (corrupt: a changed or damaged byte)");
  Film film({int(header.width), int(header.height)}, AovSet::from_bits(header.aov_bits));
  const size_t counts = film.counts_.size() * sizeof(uint32_t), depths = film.depth_.size() * sizeof(float),
               sums = film.sums_.size() * sizeof(FixedSum);
  const char* in = bytes.data() + sizeof header;
  std::memcpy(film.counts_.data(), in, counts);
  if (depths > 0) std::memcpy(film.depth_.data(), in + counts, depths);
  std::memcpy(film.sums_.data(), in + counts + depths, sums);
  film.training_.assign(in + counts + depths + sums, size_t(header.training_bytes));
  // What no render writes (a checksum can be made to match): more samples than --spp allows (a resume would try to "continue" a
  // pixel from there), or a NaN depth.
  for (uint32_t c : film.counts_)
    if (c > kMaxFilmSamples)
      throw InputError(where, "the film holds a pixel of " + std::to_string(c) + " samples; at most " +
                                  std::to_string(kMaxFilmSamples) + " are possible (corrupt)");
  for (float d : film.depth_)
    if (!(d >= 0.0f)) throw InputError(where, "the film holds a negative or NaN depth (corrupt)");
  if (key) *key = header.key;
  return film;
}

}  // namespace caligo
