#include "grids/grid_accessor_cache.h"

#include <array>
#include <optional>

#include "grids/grid_accessors.h"

namespace caligo {

struct GridAccessorCache::Slots {
  std::array<std::optional<GridAccessors>, kCapacity> entries;
  std::array<uint64_t, kCapacity> last_use{};
  uint64_t clock = 0;
};

GridAccessorCache::GridAccessorCache() : slots_(std::make_unique<Slots>()) {}
GridAccessorCache::~GridAccessorCache() = default;
GridAccessorCache::GridAccessorCache(GridAccessorCache&&) noexcept = default;
GridAccessorCache& GridAccessorCache::operator=(GridAccessorCache&&) noexcept = default;

GridAccessors& GridAccessorCache::get(const VolumeGridData& grid) {
  Slots& s = *slots_;
  ++s.clock;
  int victim = 0;
  for (int i = 0; i < kCapacity; ++i) {
    if (s.entries[i] && s.entries[i]->id == grid.id) {
      s.last_use[i] = s.clock;
      return *s.entries[i];
    }
    if (!s.entries[i] || (s.entries[victim] && s.last_use[i] < s.last_use[victim])) victim = i;
  }
  s.entries[victim].emplace(grid);
  s.last_use[victim] = s.clock;
  return *s.entries[victim];
}

}  // namespace caligo
