#include "media/medium_stack.h"

#include <algorithm>

namespace caligo {

bool MediumStack::contains(uint32_t object) const {
  return std::any_of(entries_.begin(), entries_.end(), [&](const MediumEntry& e) { return e.object == object; });
}

void MediumStack::clear() {
  entries_.clear();
  current_ = MediumState{};
}

void MediumStack::assign(const MediumStack& other) {
  entries_.assign(other.entries_.begin(), other.entries_.end());
  current_ = other.current_;
}

MediumStack::Crossing MediumStack::peek(const MediumEntry& entry) const {
  Crossing c;
  c.before = current_;
  c.after = current_;
  const auto it =
      std::find_if(entries_.begin(), entries_.end(), [&](const MediumEntry& e) { return e.object == entry.object; });
  c.entering = it == entries_.end();
  const MediumEntry* self = c.entering ? nullptr : &*it;
  // The highest priority and the most recent entry holding it, without the crossed object.
  int q = kNone;
  const MediumEntry* latest = nullptr;
  for (const MediumEntry& e : entries_) {
    if (&e == self) continue;
    if (e.priority <= q) {
      q = e.priority;
      latest = &e;
    }
  }
  c.real = entry.priority < q;
  if (c.real) c.after = c.entering ? entry.inside : (latest ? latest->inside : MediumState{});
  return c;
}

MediumStack::Crossing MediumStack::cross(const MediumEntry& entry) {
  const Crossing c = peek(entry);
  if (c.entering) {
    entries_.push_back(entry);
  } else {
    entries_.erase(std::find_if(entries_.begin(), entries_.end(),
                                [&](const MediumEntry& e) { return e.object == entry.object; }));
  }
  current_ = c.after;
  return c;
}

}  // namespace caligo
