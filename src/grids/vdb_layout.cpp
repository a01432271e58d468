// Checks an OpenVDB file's layout before OpenVDB reads it. OpenVDB trusts the file: a
// truncated one is read without complaint (missing bytes become garbage voxels or a crash)
// and an unknown format version only logs a warning. The header and the grid descriptors
// (each giving where its grid ends) are parsed here, every length bounded by the file size.
//
// Layout (openvdb/io/Archive.cc, File.cc, GridDescriptor.cc; format 222 and later):
//   int64 magic, uint32 file version, uint32 library major, uint32 library minor,
//   char has-grid-offsets, 36-char UUID, file metadata (int32 count, then per entry:
//   string name, string type, uint32 size, bytes), int32 grid count, then per grid:
//   string unique name, string type, string instance parent, int64 grid/block/end
//   positions, the grid's bytes up to its end position. A grid's bytes start with uint32
//   compression flags and the grid's metadata (as the file's). Strings are uint32 length +
//   chars. Metadata lengths are bounded here too: OpenVDB allocates and zero-fills whatever
//   length a corrupt file states (gigabytes) before noticing anything is wrong.
#include <openvdb/version.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "grids/grid_io_internal.h"

namespace caligo {
namespace {

constexpr uint32_t kMaxStringBytes = 1 << 16;
constexpr int32_t kMaxEntries = 1 << 16;

class LayoutReader {
 public:
  LayoutReader(const std::string& path, const SourceLocation& where)
      : path_(path), where_(where), in_(path, std::ios::binary) {
    std::error_code ec;
    size_ = std::filesystem::file_size(path, ec);
    if (ec || !in_) fail("cannot read the OpenVDB file");
  }

  [[noreturn]] void fail(const std::string& what) const { throw_grid_file_error(path_, where_, what); }

  template <typename T>
  T read(const char* what) {
    T value;
    bytes(&value, sizeof(T), what);
    return value;
  }

  void bytes(void* dst, uint64_t n, const char* what) {
    if (n > size_ - pos_) fail(std::string("truncated OpenVDB file (the ") + what + " is cut off)");
    if (!in_.read(static_cast<char*>(dst), std::streamsize(n))) fail("cannot read the OpenVDB file");
    pos_ += n;
  }

  std::string string(const char* what) {
    const uint32_t n = read<uint32_t>(what);
    if (n > kMaxStringBytes)
      fail(std::string("corrupt OpenVDB file (") + what + " of " + std::to_string(n) + " bytes)");
    std::string s(n, '\0');
    bytes(s.data(), n, what);
    return s;
  }

  void skip(uint64_t n, const char* what) {
    if (n > size_ - pos_) fail(std::string("truncated OpenVDB file (the ") + what + " is cut off)");
    pos_ += n;
    in_.seekg(std::streamoff(pos_));
  }

  void seek(uint64_t pos) {
    pos_ = pos;
    in_.seekg(std::streamoff(pos));
  }

  // A metadata table (int32 count, then name, type, uint32 size and value each) that must
  // end by `end`.
  void metadata(uint64_t end, const char* what) {
    const int32_t count = read<int32_t>(what);
    if (count < 0 || count > kMaxEntries) fail(std::string("corrupt OpenVDB file (") + what + " count)");
    for (int32_t i = 0; i < count; ++i) {
      string(what);
      string(what);
      const uint32_t bytes = read<uint32_t>(what);
      if (bytes > end - std::min(end, pos_)) fail(std::string("corrupt OpenVDB file (") + what + " size)");
      skip(bytes, what);
    }
  }

  uint64_t size() const { return size_; }
  uint64_t pos() const { return pos_; }

 private:
  std::string path_;
  SourceLocation where_;
  std::ifstream in_;
  uint64_t size_ = 0, pos_ = 0;
};

}  // namespace

bool check_vdb_layout(const std::string& path, const SourceLocation& where) {
  LayoutReader r(path, where);
  if (r.read<int64_t>("header") != openvdb::OPENVDB_MAGIC) r.fail("not an OpenVDB file (wrong magic number)");
  const uint32_t version = r.read<uint32_t>("header");
  if (version > openvdb::OPENVDB_FILE_VERSION)
    r.fail("OpenVDB file format " + std::to_string(version) + " is newer than this reader's (" +
           std::to_string(openvdb::OPENVDB_FILE_VERSION) + ")");
  if (version < openvdb::OPENVDB_FILE_VERSION_NODE_MASK_COMPRESSION)
    r.fail("OpenVDB file format " + std::to_string(version) + " is too old (before OpenVDB 3); re-save it");
  r.skip(8, "header");  // library version
  const bool has_offsets = r.read<char>("header") != 0;
  r.skip(36, "header");  // UUID
  r.metadata(r.size(), "file metadata");
  // Files written as streams have no descriptors to check; OpenVDB reads them sequentially
  // (and the crash probe reads them through a stream it watches: grid_vdb_read.cpp).
  if (!has_offsets) return false;
  const int32_t grids = r.read<int32_t>("grid count");
  if (grids < 0 || grids > kMaxEntries) r.fail("corrupt OpenVDB file (grid count)");
  for (int32_t i = 0; i < grids; ++i) {
    const std::string name = r.string("grid name");
    r.string("grid type");
    r.string("grid instance parent");
    const int64_t grid_pos = r.read<int64_t>("grid descriptor");
    const int64_t block_pos = r.read<int64_t>("grid descriptor");
    const int64_t end_pos = r.read<int64_t>("grid descriptor");
    if (grid_pos < int64_t(r.pos()) || block_pos < grid_pos || end_pos < block_pos)
      r.fail("corrupt OpenVDB file (grid \"" + name + "\" has inconsistent offsets)");
    if (uint64_t(end_pos) > r.size())
      r.fail("truncated OpenVDB file (grid \"" + name + "\" ends at byte " + std::to_string(end_pos) +
             ", the file has " + std::to_string(r.size()) + ")");
    r.seek(uint64_t(grid_pos));
    r.read<uint32_t>("grid compression flags");
    r.metadata(uint64_t(block_pos), "grid metadata");
    r.seek(uint64_t(end_pos));
  }
  return true;
}

}  // namespace caligo
