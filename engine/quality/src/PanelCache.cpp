#include "qv/quality/PanelCache.h"

#include <algorithm>

namespace qv {
namespace {

/// `r` minus `cut`, appended to `out` (0 to 4 rectangles: the bands above and below the cut, then
/// the pieces left and right of it within the cut's rows).
void subtract(const PixelRect& r, const PixelRect& cut, std::vector<PixelRect>& out) {
  const PixelRect overlap{std::max(r.x0, cut.x0), std::max(r.y0, cut.y0), std::min(r.x1, cut.x1),
                          std::min(r.y1, cut.y1)};
  if (overlap.empty()) {
    out.push_back(r);
    return;
  }
  const PixelRect pieces[] = {
      {r.x0, r.y0, r.x1, overlap.y0},              // above
      {r.x0, overlap.y1, r.x1, r.y1},              // below
      {r.x0, overlap.y0, overlap.x0, overlap.y1},  // left
      {overlap.x1, overlap.y0, r.x1, overlap.y1},  // right
  };
  for (const PixelRect& p : pieces) {
    if (!p.empty()) out.push_back(p);
  }
}

}  // namespace

std::vector<PixelRect> disjointCover(std::span<const PixelRect> rects, int width, int height) {
  std::vector<PixelRect> cover;
  std::vector<PixelRect> pieces, next;
  for (const PixelRect& input : rects) {
    const PixelRect clipped{std::max(input.x0, 0), std::max(input.y0, 0), std::min(input.x1, width),
                            std::min(input.y1, height)};
    if (clipped.empty()) continue;
    pieces.assign(1, clipped);
    for (const PixelRect& earlier : cover) {
      next.clear();
      for (const PixelRect& p : pieces) subtract(p, earlier, next);
      pieces.swap(next);
      if (pieces.empty()) break;
    }
    cover.insert(cover.end(), pieces.begin(), pieces.end());
  }
  return cover;
}

bool PanelRefresh::redraw(std::uint64_t contentKey, std::span<const PixelRect> rects, bool input, double nowSeconds) {
  if (input) {
    inputUntil_ = nowSeconds + options_.inputSeconds;
    inputFramesLeft_ = options_.inputFrames + 1;  // this frame and inputFrames after it
  }
  const bool afterInput = nowSeconds <= inputUntil_ || inputFramesLeft_ > 0;
  if (inputFramesLeft_ > 0) --inputFramesLeft_;
  const bool sameRects = std::equal(rects.begin(), rects.end(), shownRects_.begin(), shownRects_.end());
  if (valid_ && sameRects && contentKey == shownKey_) return false;
  const bool now = !valid_ || !sameRects || afterInput || nowSeconds - lastRedraw_ >= options_.passiveSeconds;
  if (!now) {
    ++staleFrames_;
    return false;
  }
  valid_ = true;
  shownKey_ = contentKey;
  shownRects_.assign(rects.begin(), rects.end());
  lastRedraw_ = nowSeconds;
  ++redraws_;
  return true;
}

}  // namespace qv
