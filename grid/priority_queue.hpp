#pragma once
/// The one priority queue of the grid searches (A*, LPA*, D* Lite): a binary
/// min-heap of cells indexed by CellId, with decrease/increase-key and removal
/// in O(log n) and no allocation once it has grown.
#include <cassert>
#include <compare>
#include <cstdint>
#include <vector>

#include "grid/grid_graph.hpp"

namespace campo::grid {

/// A two-part priority compared lexicographically; ties between equal keys are
/// broken by the smaller CellId, so the order of expansion is fully defined.
struct Key {
  Cost primary = 0;
  Cost secondary = 0;
  friend auto operator<=>(const Key&, const Key&) = default;
};

class IndexedHeap {
 public:
  /// Holds cells with ids in [0, id_count).
  explicit IndexedHeap(CellId id_count = 0) : position_(static_cast<std::size_t>(id_count), kAbsent) {}

  bool empty() const { return entries_.empty(); }
  std::size_t size() const { return entries_.size(); }
  bool contains(CellId id) const { return position_[id] != kAbsent; }
  CellId top() const { return entries_.front().id; }
  const Key& top_key() const { return entries_.front().key; }

  void push(CellId id, const Key& key) {
    assert(!contains(id));
    position_[id] = static_cast<std::int32_t>(entries_.size());
    entries_.push_back({key, id});
    sift_up(entries_.size() - 1);
  }

  /// Inserts `id`, or moves it to `key` if it is queued already.
  void push_or_update(CellId id, const Key& key) {
    if (!contains(id)) {
      push(id, key);
      return;
    }
    const std::size_t i = static_cast<std::size_t>(position_[id]);
    const Key old = entries_[i].key;
    entries_[i].key = key;
    if (key < old) {
      sift_up(i);
    } else {
      sift_down(i);
    }
  }

  CellId pop() {
    const CellId id = top();
    remove(id);
    return id;
  }

  /// Removes `id` if it is queued.
  void remove(CellId id) {
    if (!contains(id)) return;
    const std::size_t i = static_cast<std::size_t>(position_[id]);
    position_[id] = kAbsent;
    const Entry last = entries_.back();
    entries_.pop_back();
    if (i == entries_.size()) return;
    // Put the last entry in the hole and restore the order in whichever direction it breaks.
    entries_[i] = last;
    position_[last.id] = static_cast<std::int32_t>(i);
    sift_up(i);
    sift_down(static_cast<std::size_t>(position_[last.id]));
  }

  /// Empties the queue in O(size), keeping the capacity.
  void clear() {
    for (const Entry& e : entries_) position_[e.id] = kAbsent;
    entries_.clear();
  }

 private:
  static constexpr std::int32_t kAbsent = -1;
  struct Entry {
    Key key;
    CellId id = 0;
  };

  static bool before(const Entry& a, const Entry& b) {
    return a.key < b.key || (a.key == b.key && a.id < b.id);
  }

  void place(std::size_t i, const Entry& e) {
    entries_[i] = e;
    position_[e.id] = static_cast<std::int32_t>(i);
  }

  void sift_up(std::size_t i) {
    const Entry e = entries_[i];
    while (i > 0) {
      const std::size_t parent = (i - 1) / 2;
      if (!before(e, entries_[parent])) break;
      place(i, entries_[parent]);
      i = parent;
    }
    place(i, e);
  }

  void sift_down(std::size_t i) {
    const Entry e = entries_[i];
    const std::size_t n = entries_.size();
    while (true) {
      std::size_t child = 2 * i + 1;
      if (child >= n) break;
      if (child + 1 < n && before(entries_[child + 1], entries_[child])) ++child;
      if (!before(entries_[child], e)) break;
      place(i, entries_[child]);
      i = child;
    }
    place(i, e);
  }

  std::vector<Entry> entries_;
  std::vector<std::int32_t> position_;  ///< index in entries_ per CellId, kAbsent if not queued
};

}  // namespace campo::grid
