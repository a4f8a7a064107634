// Draws Dear ImGui's draw data (the panels) with WebGL2, re-using its buffers frame after frame.
//
// Why not ImGui's own OpenGL3 backend (Debian's 1.86): it re-specifies a vertex and an index buffer
// with glBufferData for every draw list of every frame. In Chromium each re-specification is a new
// allocation in the GPU process, and on software WebGL (SwiftShader) that alone held a page that
// draws nothing but the panel to 20 frames per second, where the same page without those uploads
// ran at 60.
//
// Here the frame's draw lists are gathered into one vertex and one index array (indices re-based
// to 32 bits, so every list and command draws from the same buffers without a base vertex, which
// WebGL2 lacks) and sent with one glBufferSubData each into one of kRing buffer pairs, used in turn
// so that a frame never overwrites what an earlier frame may still be drawing from. A pair grows
// (doubling) only when a frame needs more than it holds, and never shrinks.
//
// renderCached() keeps the panels' picture in a texture of the framebuffer's size (premultiplied
// RGBA) and redraws it only when told to (qv/quality/PanelCache.h decides when); every frame it
// copies the picture over the framebuffer within the given disjoint rectangles, one blended
// fragment per covered pixel. On a software renderer the copy costs about a quarter of drawing the
// panels' triangles.
//
// Must be created after ImGui::CreateContext() and with the WebGL2 context current; it builds the
// font atlas's texture and sets it as the atlas's texture id. Leaves blending and the scissor test
// off and no vertex array bound.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "qv/quality/PanelCache.h"

struct ImDrawData;

namespace qv {

class GlImGuiRenderer {
 public:
  GlImGuiRenderer();
  ~GlImGuiRenderer();
  GlImGuiRenderer(const GlImGuiRenderer&) = delete;
  GlImGuiRenderer& operator=(const GlImGuiRenderer&) = delete;

  /// False when the program failed to compile or link; error() says why (nothing is drawn then).
  [[nodiscard]] bool ok() const { return error_.empty(); }
  [[nodiscard]] const std::string& error() const { return error_; }

  /// Draws `data` over what the framebuffer holds (ImGui::GetDrawData() after ImGui::Render()).
  void render(const ImDrawData& data);

  /// Like render(), through the cached picture: when `redraw`, draws `data` into the picture
  /// (cleared first) and keeps `cover` (the windows' rectangles, disjoint, framebuffer pixels from
  /// the top-left: disjointCover of ui::panelRects); then, every call, copies the picture within the
  /// kept rectangles. A redraw is forced when the picture does not have the framebuffer's size.
  void renderCached(const ImDrawData& data, bool redraw, std::span<const PixelRect> cover);

  /// True when the cached picture exists at `data`'s framebuffer size (else the next
  /// renderCached() redraws it whatever it is told).
  [[nodiscard]] bool cacheFits(const ImDrawData& data) const;

  /// What the last render() drew and sent.
  struct FrameStats {
    std::uint32_t vertices = 0, indices = 0;  ///< of the panels' draw data this frame
    std::uint32_t drawCalls = 0;              ///< made this frame (the copy is one)
    std::uint64_t uploadBytes = 0;            ///< vertex and index bytes sent to the GPU this frame
    bool cached = false;                      ///< drawn through the cached picture
    bool redrawn = false;                     ///< the panels' triangles were drawn this frame
    std::uint64_t copiedPixels = 0;           ///< pixels the copy of the cached picture covered
  };
  [[nodiscard]] FrameStats lastFrame() const { return last_; }

  /// Buffer pairs used in turn.
  static constexpr int kRing = 3;

 private:
  struct Slot {
    unsigned vao = 0, vertexBuffer = 0, indexBuffer = 0;
    std::size_t vertexBytes = 0, indexBytes = 0;  // allocated
  };
  void setUpState(const ImDrawData& data, int framebufferWidth, int framebufferHeight, const Slot& slot) const;
  /// Sends `data`'s vertices and indices into the next slot of the ring and returns it.
  Slot& upload(const ImDrawData& data);
  /// Draws `data`'s commands from `slot` into the bound framebuffer.
  void drawLists(const ImDrawData& data, int framebufferWidth, int framebufferHeight, const Slot& slot);
  /// (Re)creates the cached picture at this size; false when the framebuffer is incomplete.
  bool ensureCache(int width, int height);

  std::string error_;
  unsigned program_ = 0, fontTexture_ = 0;
  int displayUniform_ = -1, textureUniform_ = -1;
  std::array<Slot, kRing> ring_{};
  int next_ = 0;
  std::vector<std::uint8_t> vertices_;  // the frame's ImDrawVert, list after list
  std::vector<std::uint32_t> indices_;  // re-based to the frame's vertex array
  FrameStats last_;

  // The cached picture and its copy.
  unsigned copyProgram_ = 0, cacheTexture_ = 0, cacheFramebuffer_ = 0, copyVao_ = 0, copyBuffer_ = 0;
  int copySizeUniform_ = -1, copyTextureUniform_ = -1;
  int cacheWidth_ = 0, cacheHeight_ = 0;
  bool cacheBroken_ = false;        // the picture could not be made: render() every frame
  std::size_t copyBytes_ = 0;       // allocated in copyBuffer_
  int copyVertices_ = 0;            // of the kept rectangles
  std::uint64_t copiedPixels_ = 0;  // their area
  std::vector<float> copyCorners_;  // scratch: the rectangles' triangles
};

}  // namespace qv
