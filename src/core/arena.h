// Per-thread bump allocation: buffers come from a thread's arena and are released all at
// once with reset(), so a hot loop never calls malloc. Not used by the renderer yet (its
// per-ray buffers are per-thread reusable vectors, see PathScratch); meant for the pooled
// interval lists of mesh and grid volumes in later stages.
#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <span>
#include <type_traits>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

namespace caligo {

class Arena {
 public:
  explicit Arena(size_t block_bytes = 64 * 1024) : block_bytes_(block_bytes) {}
  Arena(const Arena&) = delete;
  Arena& operator=(const Arena&) = delete;
  Arena(Arena&&) = default;
  Arena& operator=(Arena&&) = default;

  // Uninitialised storage for n trivially destructible objects.
  template <typename T>
  std::span<T> allocate(size_t n) {
    static_assert(std::is_trivially_destructible_v<T>, "arena memory is released without destructors");
    void* p = allocate_bytes(n * sizeof(T), alignof(T));
    return {static_cast<T*>(p), n};
  }

  // Makes every byte handed out so far reusable; keeps the blocks.
  void reset() {
    current_ = 0;
    offset_ = 0;
  }

  size_t capacity_bytes() const {
    size_t total = 0;
    for (const Block& b : blocks_) total += b.size;
    return total;
  }

 private:
  struct Block {
    std::unique_ptr<std::byte[]> data;
    size_t size;
  };

  void* allocate_bytes(size_t bytes, size_t align);

  size_t block_bytes_;
  std::vector<Block> blocks_;
  size_t current_ = 0;  // index of the block being filled
  size_t offset_ = 0;   // bytes used in that block
};

// One Arena per thread that asks for one.
class ThreadArenas {
 public:
  Arena& local() { return arenas_.local(); }

 private:
  tbb::enumerable_thread_specific<Arena> arenas_;
};

}  // namespace caligo
