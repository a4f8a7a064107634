// The panels' picture kept between frames. On a software WebGL renderer the panels (Dear ImGui's
// windows: about 3,400 blended, textured triangles) cost about 17 ms a frame to draw, where
// copying their pixels from a texture costs about 4 ms. So the app draws them into a texture only
// when what they show changes, and every frame copies the texture over the city within the
// screen rectangles the windows cover.
//
// What changes while nobody touches the panels (the time line while playing, the numbers of the
// buildings in view while the camera moves, the frame rate) is redrawn at most every
// `passiveSeconds`; a change the user caused (a click, a key, the pointer over a window) or one
// that opens, closes, moves or resizes a window is redrawn at once.
//
// Pure: no GL, no ImGui. Rectangles are in framebuffer pixels, x right and y down from the top-left.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace qv {

/// Pixels [x0, x1) x [y0, y1).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  [[nodiscard]] bool empty() const { return x1 <= x0 || y1 <= y0; }
  [[nodiscard]] long long area() const { return empty() ? 0 : static_cast<long long>(x1 - x0) * (y1 - y0); }
  bool operator==(const PixelRect&) const = default;
};

/// Rectangles that cover exactly the union of `rects` clipped to [0, width) x [0, height), none of
/// them overlapping (each rectangle minus the ones before it, in at most four pieces each), so
/// that a blended copy touches every pixel once. Empty rectangles are dropped.
[[nodiscard]] std::vector<PixelRect> disjointCover(std::span<const PixelRect> rects, int width, int height);

struct PanelRefreshOptions {
  /// Passive changes are redrawn at most this often (s); 0 redraws every change at once.
  double passiveSeconds = 0.25;
  /// After the user's input, changes are redrawn at once for this long (s): a widget answers a
  /// click a frame or two after it (ImGui samples input once a frame).
  double inputSeconds = 0.2;
  /// ... and for at least this many frames (on a slow device 0.2 s can be a single frame).
  int inputFrames = 3;
};

/// Decides, frame by frame, whether the cached picture of the panels is redrawn. Not thread-safe.
class PanelRefresh {
 public:
  explicit PanelRefresh(PanelRefreshOptions options = {}) : options_(options) {}

  /// This frame's panels: `contentKey` hashes what they draw, `rects` are the windows' screen
  /// rectangles (as drawn, in order), `input` is true when the user acted on them this frame.
  /// `nowSeconds` is a monotonic clock. Returns true when the picture must be redrawn this frame;
  /// the shown key and rectangles are then this frame's.
  bool redraw(std::uint64_t contentKey, std::span<const PixelRect> rects, bool input, double nowSeconds);

  /// The next frame is redrawn whatever it shows (the texture was lost or resized).
  void invalidate() { valid_ = false; }
  void setOptions(PanelRefreshOptions options) { options_ = options; }
  [[nodiscard]] const PanelRefreshOptions& options() const { return options_; }

  /// Redraws so far and frames that showed a picture older than their own content.
  [[nodiscard]] std::uint64_t redraws() const { return redraws_; }
  [[nodiscard]] std::uint64_t staleFrames() const { return staleFrames_; }

 private:
  PanelRefreshOptions options_;
  bool valid_ = false;
  std::uint64_t shownKey_ = 0;
  std::vector<PixelRect> shownRects_;
  double lastRedraw_ = 0.0;
  double inputUntil_ = -1.0;
  int inputFramesLeft_ = 0;
  std::uint64_t redraws_ = 0, staleFrames_ = 0;
};

}  // namespace qv
