// RangeAllocator: hands out contiguous ranges of a growing index space (rows of the GPU building
// and floor tables) and takes them back. First fit over a sorted free list; adjacent free ranges
// merge. O(free ranges) per call, which stays small because ranges come and go with whole tiles.
#pragma once

#include <cstdint>
#include <map>
#include <optional>

namespace qv {

class RangeAllocator {
 public:
  /// `capacity`: the index space is [0, capacity).
  explicit RangeAllocator(std::uint32_t capacity) : capacity_(capacity) { free_[0] = capacity; }

  /// The first index of a free range of `count`, or nullopt when none is large enough.
  std::optional<std::uint32_t> allocate(std::uint32_t count);
  /// Returns [first, first + count) to the free space. Precondition: it was allocated.
  void release(std::uint32_t first, std::uint32_t count);

  [[nodiscard]] std::uint32_t capacity() const { return capacity_; }
  [[nodiscard]] std::uint32_t used() const { return used_; }
  /// One past the highest index in use now (the part of a table that must exist); 0 when none is.
  [[nodiscard]] std::uint32_t end() const;

 private:
  std::map<std::uint32_t, std::uint32_t> free_;  // first -> count
  std::uint32_t capacity_ = 0;
  std::uint32_t used_ = 0;
};

}  // namespace qv
