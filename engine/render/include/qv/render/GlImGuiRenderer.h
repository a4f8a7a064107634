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
// Must be created after ImGui::CreateContext() and with the WebGL2 context current; it builds the
// font atlas's texture and sets it as the atlas's texture id. Leaves blending and the scissor test
// off and no vertex array bound.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

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

  /// What the last render() drew and sent.
  struct FrameStats {
    std::uint32_t vertices = 0, indices = 0, drawCalls = 0;
    std::uint64_t uploadBytes = 0;  ///< vertex and index bytes sent to the GPU
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

  std::string error_;
  unsigned program_ = 0, fontTexture_ = 0;
  int displayUniform_ = -1, textureUniform_ = -1;
  std::array<Slot, kRing> ring_{};
  int next_ = 0;
  std::vector<std::uint8_t> vertices_;  // the frame's ImDrawVert, list after list
  std::vector<std::uint32_t> indices_;  // re-based to the frame's vertex array
  FrameStats last_;
};

}  // namespace qv
