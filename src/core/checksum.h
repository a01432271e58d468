// CRC-32 (zlib's, the polynomial of PNG and gzip) over bytes and over files: the integrity
// check of checkpoints and the content key of the files a scene reads. It detects every
// single-bit error and every burst of up to 32 bits; it is not a defence against deliberate
// tampering, only against corruption.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace caligo {

// `crc` continues an earlier checksum (0 to start).
uint32_t crc32_of(std::string_view bytes, uint32_t crc = 0);

// The CRC-32 and size of a file's content, read in 1 MiB pieces. Throws InputError naming the
// file when it cannot be read.
struct FileChecksum {
  uint64_t bytes = 0;
  uint32_t crc = 0;
};
FileChecksum file_checksum(const std::string& path);

}  // namespace caligo
