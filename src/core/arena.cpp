#include "core/arena.h"

#include <algorithm>
#include <cstdint>

namespace caligo {

void* Arena::allocate_bytes(size_t bytes, size_t align) {
  for (;;) {
    if (current_ < blocks_.size()) {
      Block& b = blocks_[current_];
      const auto base = reinterpret_cast<uintptr_t>(b.data.get());
      const size_t aligned = ((base + offset_ + align - 1) & ~(uintptr_t(align) - 1)) - base;
      if (aligned + bytes <= b.size) {
        offset_ = aligned + bytes;
        return b.data.get() + aligned;
      }
      ++current_;
      offset_ = 0;
      continue;
    }
    const size_t size = std::max(block_bytes_, bytes + align);
    blocks_.push_back({std::make_unique<std::byte[]>(size), size});
  }
}

}  // namespace caligo
