#include "qv/core/RangeAllocator.h"

#include <algorithm>

namespace qv {

std::optional<std::uint32_t> RangeAllocator::allocate(std::uint32_t count) {
  if (count == 0) return std::nullopt;
  for (auto it = free_.begin(); it != free_.end(); ++it) {
    if (it->second < count) continue;
    const std::uint32_t first = it->first;
    const std::uint32_t rest = it->second - count;
    free_.erase(it);
    if (rest > 0) free_[first + count] = rest;
    used_ += count;
    return first;
  }
  return std::nullopt;
}

std::uint32_t RangeAllocator::end() const {
  if (free_.empty()) return capacity_;
  const auto& last = *free_.rbegin();
  return last.first + last.second == capacity_ ? last.first : capacity_;
}

void RangeAllocator::release(std::uint32_t first, std::uint32_t count) {
  if (count == 0) return;
  used_ -= std::min(used_, count);
  auto [it, inserted] = free_.emplace(first, count);
  if (!inserted) return;  // double release: ignore rather than corrupt the list
  // Merge with the next and previous free ranges.
  auto next = std::next(it);
  if (next != free_.end() && it->first + it->second == next->first) {
    it->second += next->second;
    free_.erase(next);
  }
  if (it != free_.begin()) {
    auto prev = std::prev(it);
    if (prev->first + prev->second == it->first) {
      prev->second += it->second;
      free_.erase(it);
    }
  }
}

}  // namespace qv
