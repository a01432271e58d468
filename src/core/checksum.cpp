#include "core/checksum.h"

#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <vector>

#include "core/error.h"

namespace caligo {

uint32_t crc32_of(std::string_view bytes, uint32_t crc) {
  // zlib takes lengths as uInt: long inputs go in pieces.
  const char* p = bytes.data();
  size_t left = bytes.size();
  uLong c = crc;
  while (left > 0) {
    const uInt n = uInt(std::min<size_t>(left, size_t(1) << 30));
    c = ::crc32(c, reinterpret_cast<const Bytef*>(p), n);
    p += n;
    left -= n;
  }
  return uint32_t(c);
}

FileChecksum file_checksum(const std::string& path) {
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) throw InputError(SourceLocation{path, ""}, "cannot read the file for its checksum");
  std::vector<char> buffer(size_t(1) << 20);
  FileChecksum sum;
  for (;;) {
    const size_t n = std::fread(buffer.data(), 1, buffer.size(), f.get());
    sum.crc = crc32_of({buffer.data(), n}, sum.crc);
    sum.bytes += n;
    if (n < buffer.size()) break;
  }
  if (std::ferror(f.get())) throw InputError(SourceLocation{path, ""}, "read error while taking the file's checksum");
  return sum;
}

}  // namespace caligo
