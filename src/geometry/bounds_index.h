// An Embree BVH over boxes, answering "which boxes does this ray pass through?" in
// O(log n). Volume primitives use it to find their intervals along a ray; the exact shape
// test is theirs, the index only prunes.
//
// Thread safety: add() and commit() on one thread; candidates() concurrently afterwards.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/bounds.h"
#include "core/ray.h"

namespace caligo {

class BoundsIndex {
 public:
  BoundsIndex();
  ~BoundsIndex();
  BoundsIndex(BoundsIndex&&) noexcept;
  BoundsIndex& operator=(BoundsIndex&&) noexcept;

  // Returns the box's id (dense, in order of addition). Throws std::invalid_argument for a
  // box with non-finite or inverted corners.
  uint32_t add(const Bounds3& box);
  void commit();
  size_t size() const;

  // Ids of every box the ray's [tmin, tmax] range overlaps, in no particular order; `out`
  // is cleared first and reused.
  void candidates(const Ray& ray, std::vector<uint32_t>& out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace caligo
