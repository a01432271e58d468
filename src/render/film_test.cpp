// The AOV film: exact sums that merge bit for bit however samples are split, per-pixel counts,
// the raw file round trip and its located errors, and the AOV list parser.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <unistd.h>

#include "core/checksum.h"
#include "core/error.h"
#include "core/rng.h"
#include "render/film.h"

namespace caligo {
namespace {

constexpr Vec2i kSize{7, 5};

// A sample with values spread over many magnitudes (where float sums depend on order).
PathSample random_sample(Pcg32& rng) {
  PathSample s;
  for (RGB& l : s.light) {
    const float scale = std::exp2(float(int(rng.next_u32() % 40)) - 20.0f);
    l = RGB(rng.next_float() * scale, rng.next_float() * scale, rng.next_float() * scale);
  }
  s.alpha = rng.next_float();
  s.normal = {rng.next_float(), -rng.next_float(), 0.5f};
  s.albedo = RGB(rng.next_float());
  s.hit_t = 1.0f + rng.next_float();
  return s;
}

// Adds samples [first, last) of every pixel, each pixel's sequence fixed by its seed.
void add_range(Film& film, int first, int last) {
  for (int y = 0; y < kSize.y; ++y)
    for (int x = 0; x < kSize.x; ++x) {
      Pcg32 rng(uint64_t(y * kSize.x + x), 7);
      for (int s = 0; s < last; ++s) {
        const PathSample sample = random_sample(rng);
        if (s >= first) film.add(x, y, sample, sample.hit_t);
      }
    }
}

TEST(Film, MergedSampleRangesEqualOneFilmBitForBit) {
  Film whole(kSize, AovSet::all());
  add_range(whole, 0, 64);
  Film a(kSize, AovSet::all()), b(kSize, AovSet::all()), c(kSize, AovSet::all());
  add_range(a, 0, 13);
  add_range(b, 13, 40);
  add_range(c, 40, 64);
  Film cba = c;
  cba.merge(b);
  cba.merge(a);  // another order, too
  a.merge(b);
  a.merge(c);
  EXPECT_TRUE(a == whole);
  EXPECT_TRUE(cba == whole);
  EXPECT_TRUE(a.resolve() == whole.resolve());
  // Float sums would not be exact here: the same values summed in the two orders differ.
  float forward = 0.0f, backward = 0.0f;
  Pcg32 rng(3, 7);
  std::vector<float> values;
  for (int i = 0; i < 64; ++i) values.push_back(random_sample(rng).light[0].r);
  for (float v : values) forward += v;
  for (auto it = values.rbegin(); it != values.rend(); ++it) backward += *it;
  EXPECT_NE(forward, backward) << "the test's values do not exercise rounding";
}

TEST(Film, ResolveAveragesEachPixelOverItsOwnCount) {
  Film film({2, 1}, AovSet::defaults());
  PathSample s;
  s.add(LightKind::kSurfaceDirect, RGB(2.0f));
  s.alpha = 1.0f;
  film.add(0, 0, s, 3.0f);
  film.add(0, 0, PathSample{}, 5.0f);  // a second sample of zero radiance
  film.add(1, 0, s, 4.0f);
  EXPECT_EQ(film.sample_count(0, 0), 2u);
  EXPECT_EQ(film.sample_count(1, 0), 1u);
  const Image image = film.resolve();
  EXPECT_FLOAT_EQ(image.at(0, 0, 0), 1.0f);
  EXPECT_FLOAT_EQ(image.at(1, 0, 0), 2.0f);
  EXPECT_FLOAT_EQ(image.at(0, 0, image.channel_index("A")), 0.5f);
  EXPECT_FLOAT_EQ(image.at(0, 0, image.channel_index("Z")), 3.0f);  // the nearest depth
  EXPECT_FLOAT_EQ(image.at(1, 0, image.channel_index("Z")), 4.0f);
}

TEST(Film, LightLayersAddUpToTheBeauty) {
  Film film(kSize, AovSet::all());
  add_range(film, 0, 16);
  const Image image = film.resolve();
  for (int y = 0; y < kSize.y; ++y)
    for (int x = 0; x < kSize.x; ++x) {
      RGB layers;
      for (int k = 0; k < kLightKindCount; ++k) {
        const auto rgb = image.rgb_indices(std::string(aov_name(light_aov(LightKind(k)))) + ".");
        ASSERT_TRUE(rgb);
        layers += image.rgb(x, y, *rgb);
      }
      const RGB beauty = image.rgb(x, y, 0);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(layers[c], beauty[c], 1e-5f * beauty[c]);
    }
}

TEST(Film, NonFiniteRadianceCountsAsZero) {
  Film film({1, 1}, AovSet::all());
  PathSample bad;
  bad.add(LightKind::kVolumeDirect, RGB(std::nanf(""), 1.0f, 1.0f));
  bad.add(LightKind::kBackground, RGB(3.0f));
  film.add(0, 0, bad, kInfinity);
  PathSample good;
  good.add(LightKind::kBackground, RGB(4.0f));
  film.add(0, 0, good, kInfinity);
  const Image image = film.resolve();
  EXPECT_FLOAT_EQ(image.at(0, 0, 0), 2.0f);
  EXPECT_FLOAT_EQ(image.at(0, 0, image.channel_index("background.R")), 2.0f);
}

std::filesystem::path temp_file(const char* name) {
  return std::filesystem::temp_directory_path() / (std::string("caligo_film_") + std::to_string(::getpid()) + name);
}

TEST(Film, SaveLoadRoundTripsExactly) {
  Film film(kSize, AovSet::defaults().with(Aov::kVolumeDirect));
  add_range(film, 0, 9);
  const auto path = temp_file("_roundtrip.film");
  film.save(path.string(), 0x1234abcdull);
  uint64_t key = 0;
  const Film back = Film::load(path.string(), &key);
  EXPECT_EQ(key, 0x1234abcdull);
  EXPECT_TRUE(back == film);
  std::filesystem::remove(path);
}

TEST(Film, BadFilmFilesAreLocatedErrors) {
  Film film(kSize, AovSet::defaults());
  add_range(film, 0, 2);
  const auto path = temp_file("_bad.film");
  film.save(path.string());
  const auto size = std::filesystem::file_size(path);
  const auto expect_error = [&](const char* what) {
    try {
      Film::load(path.string());
      ADD_FAILURE() << "no error for " << what;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
  };
  std::filesystem::resize_file(path, size - 1);
  expect_error("a truncated file");
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << "P6\n7 5\n255\n";
  }
  expect_error("another format");
  std::filesystem::remove(path);
  expect_error("a missing file");
}

// The in-memory bytes (sent between MPI ranks) are the saved file's bytes; both round-trip exactly.
TEST(Film, BytesAreTheSavedFileAndRoundTrip) {
  for (const AovSet aovs : {AovSet{}, AovSet::defaults(), AovSet::all()}) {
    Film film(kSize, aovs);
    add_range(film, 0, 5);
    const std::string bytes = film.to_bytes(42);
    const auto path = temp_file("_bytes.film");
    film.save(path.string(), 42);
    std::ifstream in(path, std::ios::binary);
    const std::string saved((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::filesystem::remove(path);
    EXPECT_EQ(bytes, saved);
    uint64_t key = 0;
    EXPECT_TRUE(Film::from_bytes(bytes, "film from rank 1", &key) == film);
    EXPECT_EQ(key, 42u);
    try {
      Film::from_bytes(std::string_view(bytes).substr(0, bytes.size() - 1), "film from rank 1");
      ADD_FAILURE() << "no error for truncated bytes";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("film from rank 1"), std::string::npos) << e.what();
    }
  }
}

TEST(Film, MergeRefusesAnotherShape) {
  Film a(kSize, AovSet::defaults()), b({3, 3}, AovSet::defaults()), c(kSize, AovSet::all());
  EXPECT_THROW(a.merge(b), std::invalid_argument);
  EXPECT_THROW(a.merge(c), std::invalid_argument);
}

TEST(AovSet, ParsesNamesAndRejectsUnknownOnes) {
  EXPECT_EQ(AovSet::parse("beauty"), AovSet{});
  EXPECT_EQ(AovSet::parse("default"), AovSet::defaults());
  EXPECT_EQ(AovSet::parse("alpha,volume.direct"), AovSet{}.with(Aov::kAlpha).with(Aov::kVolumeDirect));
  EXPECT_TRUE(AovSet::parse("lights").has(Aov::kBackground));
  EXPECT_FALSE(AovSet::parse("lights").has(Aov::kAlpha));
  EXPECT_EQ(AovSet::parse("all"), AovSet::all());
  EXPECT_THROW(AovSet::parse("alpha,bogus"), InputError);
  EXPECT_THROW(AovSet::parse(""), InputError);
  EXPECT_EQ(aov_channels(AovSet{}.with(Aov::kDepth).with(Aov::kSurfaceDirect)),
            (std::vector<std::string>{"R", "G", "B", "Z", "surface_direct.R", "surface_direct.G", "surface_direct.B"}));
}

}  // namespace
}  // namespace caligo

namespace caligo {
namespace {

// The variance layer is the variance of each pixel's mean, and estimated_rmse its root mean:
// checked against the same statistics computed directly from the samples.
TEST(Film, VarianceLayerIsTheVarianceOfThePixelMean) {
  Film film({2, 1}, AovSet{}.with(Aov::kVariance));
  Pcg32 rng(9, 1);
  double sum[2] = {0, 0}, sum2[2] = {0, 0};
  const int n[2] = {50, 7};
  for (int x = 0; x < 2; ++x)
    for (int i = 0; i < n[x]; ++i) {
      const float v = rng.next_float() * 4.0f;
      PathSample s;
      s.add(LightKind::kBackground, RGB(v, v, v));
      film.add(x, 0, s, kInfinity);
      sum[x] += v;
      sum2[x] += double(v) * v;
    }
  const Image image = film.resolve();
  double mean_var = 0.0;
  for (int x = 0; x < 2; ++x) {
    const double mean = sum[x] / n[x];
    const double var_of_mean = (sum2[x] / n[x] - mean * mean) / (n[x] - 1);
    EXPECT_NEAR(image.at(x, 0, image.channel_index("variance.G")), var_of_mean, 1e-6 * (1.0 + var_of_mean));
    mean_var += var_of_mean / 2.0;
  }
  ASSERT_TRUE(film.estimated_rmse());
  EXPECT_NEAR(*film.estimated_rmse(), std::sqrt(mean_var), 1e-6);
  EXPECT_FALSE(Film({1, 1}, AovSet::defaults()).estimated_rmse());
}

}  // namespace
}  // namespace caligo

namespace caligo {
namespace {

// Hostile checkpoints: a header claiming a huge film is refused before anything of that size is
// allocated; a pixel count no render writes (2^31) is refused rather than "continued".
// Recomputes a film file's trailing CRC-32 after an edit, as a deliberate forger would.
void reseal(std::string& bytes) {
  const uint32_t crc = crc32_of(std::string_view(bytes).substr(0, bytes.size() - 4));
  std::memcpy(bytes.data() + bytes.size() - 4, &crc, 4);
}

TEST(Film, HostileFilmFilesAreRefusedBeforeAllocating) {
  Film film({2, 2}, AovSet::defaults());
  film.add(0, 0, PathSample{}, 1.0f);
  std::string bytes = film.to_bytes();
  std::string huge = bytes.substr(0, 48);
  const uint32_t side = 65536;
  std::memcpy(huge.data() + 16, &side, 4);  // width
  std::memcpy(huge.data() + 20, &side, 4);  // height
  EXPECT_THROW(Film::from_bytes(huge, "huge.ckpt"), InputError);
  const auto path = std::filesystem::temp_directory_path() / "caligo_film_huge.ckpt";
  std::ofstream(path, std::ios::binary) << huge;
  EXPECT_THROW(Film::load(path.string()), InputError);
  std::filesystem::remove(path);
  // A crafted file whose checksum matches still meets the value checks.
  const uint32_t absurd = 0x80000000u;
  std::memcpy(bytes.data() + 48, &absurd, 4);  // the first pixel's count
  reseal(bytes);
  try {
    Film::from_bytes(bytes, "counts.ckpt");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("2147483648 samples"), std::string::npos) << e.what();
  }
}

// The message of from_bytes' refusal, or "" when it accepts.
std::string refusal(const std::string& bytes) {
  try {
    Film::from_bytes(bytes, "c.ckpt");
    return "";
  } catch (const InputError& e) {
    return e.what();
  }
}

// Every kind of damage a disk, a copy or a hand can do is refused, naming the file: a flipped
// bit in a sum, a zeroed or altered sample count, a changed header field, a negative depth.
TEST(Film, CorruptCheckpointsAreRefused) {
  Film film({3, 2}, AovSet::defaults());
  for (int i = 0; i < 6; ++i) film.add(i % 3, i / 3, PathSample{}, 1.0f);
  const std::string clean = film.to_bytes(77);
  ASSERT_EQ(refusal(clean), "");
  const size_t header = 48, counts = header, depths = counts + 6 * 4, sums = depths + 6 * 4;
  for (size_t bit = 0; bit < 8 * (clean.size() - 4); bit += 97) {  // every 97th bit of the file
    std::string flipped = clean;
    flipped[bit / 8] = char(flipped[bit / 8] ^ (1 << (bit % 8)));
    const std::string why = refusal(flipped);
    EXPECT_NE(why.find("c.ckpt"), std::string::npos) << "bit " << bit << ": " << why;
  }
  std::string zeroed = clean;
  std::memset(zeroed.data() + counts + 4, 0, 4);
  EXPECT_NE(refusal(zeroed).find("checksum"), std::string::npos);
  std::string altered = clean;
  altered[counts] = 2;
  EXPECT_NE(refusal(altered).find("checksum"), std::string::npos);
  std::string sum_bit = clean;
  sum_bit[sums + 5] ^= 0x10;
  EXPECT_NE(refusal(sum_bit).find("checksum"), std::string::npos);
  std::string negative = clean;
  const float minus = -1.0f;
  std::memcpy(negative.data() + depths, &minus, 4);
  EXPECT_NE(refusal(negative).find("checksum"), std::string::npos);
  reseal(negative);
  EXPECT_NE(refusal(negative).find("negative"), std::string::npos);
}

// The training state (a guided render's field) travels with the sums, under the checksum.
TEST(Film, TheTrainingStateIsSavedWithTheSums) {
  Film film({2, 2}, AovSet::defaults());
  film.add(1, 1, PathSample{}, 1.0f);
  film.set_training_state("learnt bytes");
  const std::string bytes = film.to_bytes();
  EXPECT_EQ(Film::from_bytes(bytes, "t.ckpt").training_state(), "learnt bytes");
  std::string changed = bytes;
  changed[bytes.size() - 6] ^= 1;  // inside the training state
  EXPECT_NE(refusal(changed).find("checksum"), std::string::npos);
  EXPECT_NE(refusal(bytes.substr(0, bytes.size() - 3)).find("c.ckpt"), std::string::npos);
}

}  // namespace
}  // namespace caligo
