#include "core/checksum.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"

namespace caligo {
namespace {

// The standard check value of CRC-32 (ISO-HDLC): "123456789" -> 0xCBF43926.
TEST(Checksum, MatchesTheStandardCheckValueAndContinues) {
  EXPECT_EQ(crc32_of("123456789"), 0xCBF43926u);
  EXPECT_EQ(crc32_of("6789", crc32_of("12345")), 0xCBF43926u);
  EXPECT_EQ(crc32_of(""), 0u);
}

TEST(Checksum, EverySingleBitFlipChangesIt) {
  std::string bytes(4096, '\0');
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = char(i * 131 + 7);
  const uint32_t clean = crc32_of(bytes);
  for (size_t bit = 0; bit < bytes.size() * 8; bit += 61) {
    std::string flipped = bytes;
    flipped[bit / 8] = char(flipped[bit / 8] ^ (1 << (bit % 8)));
    EXPECT_NE(crc32_of(flipped), clean) << bit;
  }
}

TEST(Checksum, OfAFileIsOfItsBytes) {
  const auto path = std::filesystem::temp_directory_path() / ("caligo-crc-" + std::to_string(::getpid()));
  std::string bytes(3 << 20, 'x');  // three pieces
  bytes[123456] = 'y';
  std::ofstream(path, std::ios::binary) << bytes;
  const FileChecksum sum = file_checksum(path.string());
  EXPECT_EQ(sum.bytes, bytes.size());
  EXPECT_EQ(sum.crc, crc32_of(bytes));
  std::filesystem::remove(path);
  EXPECT_THROW(file_checksum(path.string()), InputError);
}

}  // namespace
}  // namespace caligo
