// The per-ray stack of surface-defined media (nested dielectrics: Schmidt & Budge, "Simple
// Nested Dielectrics in Ray Traced Images", JGT 2002, with the rules the seed adds for equal
// priorities, shadow rays and the starting stack; docs/techniques.md "Media inside surfaces").
//
// A closed surface (or an open one such as a water plane) whose material has a priority other
// than Off bounds a medium: its interior medium (or vacuum) with an IOR relative to vacuum.
// Priorities are integers, smaller is higher; Off (0) objects never enter the stack and are
// always seen. The stack holds every such object the ray is inside, in the order entered,
// identified by its surface (geometry id): a crossing of an object on the stack leaves it, any
// other crossing enters it.
//
// Rules at a crossing of object X with priority p (q: the highest priority on the stack
// without X; none: lower than any):
//   - entering X is a REAL hit iff p < q; otherwise (equal or lower priority) it is a false
//     hit: X is pushed, nothing is seen, the ray's medium does not change;
//   - leaving X is a REAL hit iff p < q; otherwise a false hit: X is removed, nothing is seen;
//   - the ray's medium (the "current" one) changes only at real hits: entering X it becomes X's;
//     leaving X it becomes that of the most recently entered object of priority q (vacuum on an
//     empty stack). Equal priorities therefore MERGE: crossings between objects of equal
//     priority are false hits, and leaving one while inside another of equal priority keeps the
//     medium of the one being left (no discontinuity where two merged objects meet).
// A real hit on a dielectric refracts with the IORs of the media actually on either side
// (Crossing::before, Crossing::after), so a liquid modelled slightly overlapping its glass
// refracts glass -> liquid, never through an air gap.
//
// Storage grows as needed (reused from path to path through the caller's scratch), so the
// stack never overflows; leaving is decided by membership, so it never underflows.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace caligo {

// The medium a ray travels in: a slot of the VolumeScene's media (Scene::medium_entry maps a
// material's interior to it; -1: vacuum) and its IOR.
struct MediumState {
  int medium = -1;
  float ior = 1.0f;
  bool operator==(const MediumState&) const = default;
};

struct MediumEntry {
  uint32_t object = 0;  // the bounding surface's geometry id
  int priority = 0;     // > 0
  MediumState inside;
};

// Named priority levels (Imageworks' menu; the gaps leave room between levels).
inline constexpr int kPriorityOff = 0;
inline constexpr int kPriorityVeryHigh = 50;
inline constexpr int kPriorityHigh = 100;
inline constexpr int kPriorityNormal = 200;
inline constexpr int kPriorityLow = 300;
inline constexpr int kPriorityVeryLow = 400;

class MediumStack {
 public:
  struct Crossing {
    bool real = false;      // the surface is seen; false: only the stack changed
    bool entering = false;  // X was not on the stack before
    MediumState before, after;  // the ray's medium on the incident and the far side
  };

  // Applies the rules to one crossing of `entry.object` (entry.priority must be > 0).
  Crossing cross(const MediumEntry& entry);
  // What cross() would answer, without changing the stack (a dielectric's crossing happens
  // only if the path transmits).
  Crossing peek(const MediumEntry& entry) const;

  // The medium the ray is in now.
  const MediumState& current() const { return current_; }
  bool empty() const { return entries_.empty(); }
  size_t size() const { return entries_.size(); }
  std::span<const MediumEntry> entries() const { return entries_; }
  bool contains(uint32_t object) const;
  void clear();
  // Copies another stack's state, reusing this one's storage.
  void assign(const MediumStack& other);

 private:
  static constexpr int kNone = std::numeric_limits<int>::max();  // below every priority

  std::vector<MediumEntry> entries_;  // in the order entered
  MediumState current_;
};

}  // namespace caligo
