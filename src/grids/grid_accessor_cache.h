// Per-thread lookup state for VolumeGrids: NanoVDB ReadAccessors for the few grids a thread
// used last, so a thread that queries the same grid repeatedly reuses one accessor (and its
// cached path to the last leaf) per channel. Never share one cache between threads. Cheap to
// construct; the header includes no NanoVDB so per-thread render state can hold one.
#pragma once

#include <cstdint>
#include <memory>

namespace caligo {

struct VolumeGridData;
struct GridAccessors;  // grids/grid_accessors.h

class GridAccessorCache {
 public:
  GridAccessorCache();
  ~GridAccessorCache();
  GridAccessorCache(GridAccessorCache&&) noexcept;
  GridAccessorCache& operator=(GridAccessorCache&&) noexcept;

  // The accessors for `grid`, made on first use; evicts the least recently used entry when full.
  GridAccessors& get(const VolumeGridData& grid);

  static constexpr int kCapacity = 4;

 private:
  struct Slots;
  std::unique_ptr<Slots> slots_;
};

}  // namespace caligo
