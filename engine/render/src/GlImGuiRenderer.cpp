#include "qv/render/GlImGuiRenderer.h"

#include <GLES3/gl3.h>
#include <imgui.h>

#include <cstddef>
#include <cstring>
#include <string>
#include <utility>

#include "Shaders.h"

namespace qv {
namespace {

void* byteOffset(std::size_t offset) {
  return reinterpret_cast<void*>(offset);  // NOLINT(performance-no-int-to-ptr): GL's offset convention
}

/// Capacity for `needed` bytes: doubling from `current` (at least 64 KiB), so growth is rare.
std::size_t grownCapacity(std::size_t current, std::size_t needed) {
  std::size_t capacity = current > 0 ? current : std::size_t{64} << 10;
  while (capacity < needed) capacity *= 2;
  return capacity;
}

}  // namespace

GlImGuiRenderer::GlImGuiRenderer() {
  program_ = shaders::linkProgram(shaders::kUiVertex, shaders::kUiFragment, error_);
  if (program_ == 0) return;
  displayUniform_ = glGetUniformLocation(program_, "u_display");
  textureUniform_ = glGetUniformLocation(program_, "u_texture");

  ImGuiIO& io = ImGui::GetIO();
  io.BackendRendererName = "qv_gles3";
  io.BackendFlags |= ImGuiBackendFlags_RendererHasVtxOffset;  // indices are re-based here

  unsigned char* pixels = nullptr;
  int width = 0, height = 0;
  io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
  glGenTextures(1, &fontTexture_);
  glBindTexture(GL_TEXTURE_2D, fontTexture_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glBindTexture(GL_TEXTURE_2D, 0);
  io.Fonts->SetTexID(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(fontTexture_)));

  for (Slot& slot : ring_) {
    glGenVertexArrays(1, &slot.vao);
    glGenBuffers(1, &slot.vertexBuffer);
    glGenBuffers(1, &slot.indexBuffer);
    glBindVertexArray(slot.vao);
    glBindBuffer(GL_ARRAY_BUFFER, slot.vertexBuffer);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, slot.indexBuffer);
    constexpr auto stride = static_cast<GLsizei>(sizeof(ImDrawVert));
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride, byteOffset(offsetof(ImDrawVert, pos)));
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, stride, byteOffset(offsetof(ImDrawVert, uv)));
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, stride, byteOffset(offsetof(ImDrawVert, col)));
    glBindVertexArray(0);
  }
}

GlImGuiRenderer::~GlImGuiRenderer() {
  for (Slot& slot : ring_) {
    glDeleteVertexArrays(1, &slot.vao);
    glDeleteBuffers(1, &slot.vertexBuffer);
    glDeleteBuffers(1, &slot.indexBuffer);
  }
  if (fontTexture_ != 0) glDeleteTextures(1, &fontTexture_);
  if (program_ != 0) glDeleteProgram(program_);
  if (cacheFramebuffer_ != 0) glDeleteFramebuffers(1, &cacheFramebuffer_);
  if (cacheTexture_ != 0) glDeleteTextures(1, &cacheTexture_);
  if (copyVao_ != 0) glDeleteVertexArrays(1, &copyVao_);
  if (copyBuffer_ != 0) glDeleteBuffers(1, &copyBuffer_);
  if (copyProgram_ != 0) glDeleteProgram(copyProgram_);
}

void GlImGuiRenderer::setUpState(const ImDrawData& data, int framebufferWidth, int framebufferHeight,
                                 const Slot& slot) const {
  glViewport(0, 0, framebufferWidth, framebufferHeight);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glDisable(GL_CULL_FACE);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  glEnable(GL_SCISSOR_TEST);
  glUseProgram(program_);
  glUniform4f(displayUniform_, data.DisplayPos.x, data.DisplayPos.y, 2.0f / data.DisplaySize.x,
              -2.0f / data.DisplaySize.y);
  glUniform1i(textureUniform_, 0);
  glActiveTexture(GL_TEXTURE0);
  glBindVertexArray(slot.vao);
}

GlImGuiRenderer::Slot& GlImGuiRenderer::upload(const ImDrawData& data) {
  // The frame's vertices list after list; each command's indices re-based to that array.
  vertices_.resize(static_cast<std::size_t>(data.TotalVtxCount) * sizeof(ImDrawVert));
  indices_.resize(static_cast<std::size_t>(data.TotalIdxCount));
  std::size_t vertexBase = 0, indexBase = 0;
  for (int n = 0; n < data.CmdListsCount; ++n) {
    const ImDrawList& list = *data.CmdLists[n];
    std::memcpy(vertices_.data() + vertexBase * sizeof(ImDrawVert), list.VtxBuffer.Data,
                static_cast<std::size_t>(list.VtxBuffer.Size) * sizeof(ImDrawVert));
    for (const ImDrawCmd& cmd : list.CmdBuffer) {
      if (cmd.UserCallback != nullptr) continue;
      const std::size_t base = vertexBase + cmd.VtxOffset;
      for (unsigned i = 0; i < cmd.ElemCount; ++i) {
        indices_[indexBase + cmd.IdxOffset + i] =
            static_cast<std::uint32_t>(base + list.IdxBuffer[static_cast<int>(cmd.IdxOffset + i)]);
      }
    }
    vertexBase += static_cast<std::size_t>(list.VtxBuffer.Size);
    indexBase += static_cast<std::size_t>(list.IdxBuffer.Size);
  }

  Slot& slot = ring_[static_cast<std::size_t>(next_)];
  next_ = (next_ + 1) % kRing;
  glBindVertexArray(slot.vao);
  const std::size_t vertexBytes = vertices_.size();
  const std::size_t indexBytes = indices_.size() * sizeof(std::uint32_t);
  glBindBuffer(GL_ARRAY_BUFFER, slot.vertexBuffer);
  if (vertexBytes > slot.vertexBytes) {
    slot.vertexBytes = grownCapacity(slot.vertexBytes, vertexBytes);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(slot.vertexBytes), nullptr, GL_DYNAMIC_DRAW);
  }
  glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(vertexBytes), vertices_.data());
  if (indexBytes > slot.indexBytes) {
    slot.indexBytes = grownCapacity(slot.indexBytes, indexBytes);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(slot.indexBytes), nullptr, GL_DYNAMIC_DRAW);
  }
  glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(indexBytes), indices_.data());
  last_.uploadBytes += vertexBytes + indexBytes;
  return slot;
}

void GlImGuiRenderer::drawLists(const ImDrawData& data, int framebufferWidth, int framebufferHeight, const Slot& slot) {
  setUpState(data, framebufferWidth, framebufferHeight, slot);
  const ImVec2 clipOffset = data.DisplayPos;
  const ImVec2 clipScale = data.FramebufferScale;
  unsigned boundTexture = ~0u;
  std::size_t indexBase = 0;
  for (int n = 0; n < data.CmdListsCount; ++n) {
    const ImDrawList& list = *data.CmdLists[n];
    for (const ImDrawCmd& cmd : list.CmdBuffer) {
      if (cmd.UserCallback != nullptr) {
        if (cmd.UserCallback == ImDrawCallback_ResetRenderState) {
          setUpState(data, framebufferWidth, framebufferHeight, slot);
          boundTexture = ~0u;
        } else {
          cmd.UserCallback(&list, &cmd);
        }
        continue;
      }
      // The clip rectangle in framebuffer pixels (GL's scissor counts rows from the bottom).
      const float minX = (cmd.ClipRect.x - clipOffset.x) * clipScale.x;
      const float minY = (cmd.ClipRect.y - clipOffset.y) * clipScale.y;
      const float maxX = (cmd.ClipRect.z - clipOffset.x) * clipScale.x;
      const float maxY = (cmd.ClipRect.w - clipOffset.y) * clipScale.y;
      if (maxX <= minX || maxY <= minY || cmd.ElemCount == 0) continue;
      glScissor(static_cast<int>(minX), static_cast<int>(static_cast<float>(framebufferHeight) - maxY),
                static_cast<int>(maxX - minX), static_cast<int>(maxY - minY));
      const auto texture = static_cast<unsigned>(reinterpret_cast<std::uintptr_t>(cmd.GetTexID()));
      if (texture != boundTexture) {
        glBindTexture(GL_TEXTURE_2D, texture);
        boundTexture = texture;
      }
      glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(cmd.ElemCount), GL_UNSIGNED_INT,
                     byteOffset((indexBase + cmd.IdxOffset) * sizeof(std::uint32_t)));
      ++last_.drawCalls;
    }
    indexBase += static_cast<std::size_t>(list.IdxBuffer.Size);
  }
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glBindVertexArray(0);
}

namespace {

/// The framebuffer size `data` is drawn at (0 x 0 when it draws nothing).
std::pair<int, int> framebufferSize(const ImDrawData& data) {
  return {static_cast<int>(data.DisplaySize.x * data.FramebufferScale.x),
          static_cast<int>(data.DisplaySize.y * data.FramebufferScale.y)};
}

}  // namespace

void GlImGuiRenderer::render(const ImDrawData& data) {
  last_ = FrameStats{};
  const auto [framebufferWidth, framebufferHeight] = framebufferSize(data);
  if (!ok() || !data.Valid || framebufferWidth <= 0 || framebufferHeight <= 0 || data.TotalVtxCount <= 0) return;
  last_.vertices = static_cast<std::uint32_t>(data.TotalVtxCount);
  last_.indices = static_cast<std::uint32_t>(data.TotalIdxCount);
  last_.redrawn = true;
  const Slot& slot = upload(data);
  drawLists(data, framebufferWidth, framebufferHeight, slot);
}

bool GlImGuiRenderer::cacheFits(const ImDrawData& data) const {
  const auto [width, height] = framebufferSize(data);
  return cacheFramebuffer_ != 0 && width == cacheWidth_ && height == cacheHeight_;
}

bool GlImGuiRenderer::ensureCache(int width, int height) {
  if (copyProgram_ == 0) {
    std::string error;
    copyProgram_ = shaders::linkProgram(shaders::kUiCopyVertex, shaders::kUiCopyFragment, error);
    if (copyProgram_ == 0) return false;
    copySizeUniform_ = glGetUniformLocation(copyProgram_, "u_size");
    copyTextureUniform_ = glGetUniformLocation(copyProgram_, "u_texture");
    glGenVertexArrays(1, &copyVao_);
    glGenBuffers(1, &copyBuffer_);
    glBindVertexArray(copyVao_);
    glBindBuffer(GL_ARRAY_BUFFER, copyBuffer_);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 2 * sizeof(float), nullptr);
    glBindVertexArray(0);
  }
  if (cacheFramebuffer_ != 0 && width == cacheWidth_ && height == cacheHeight_) return true;
  if (cacheTexture_ == 0) glGenTextures(1, &cacheTexture_);
  if (cacheFramebuffer_ == 0) glGenFramebuffers(1, &cacheFramebuffer_);
  glBindTexture(GL_TEXTURE_2D, cacheTexture_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glBindTexture(GL_TEXTURE_2D, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, cacheFramebuffer_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, cacheTexture_, 0);
  const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  cacheWidth_ = complete ? width : 0;
  cacheHeight_ = complete ? height : 0;
  return complete;
}

void GlImGuiRenderer::renderCached(const ImDrawData& data, bool redraw, std::span<const PixelRect> cover) {
  const auto [framebufferWidth, framebufferHeight] = framebufferSize(data);
  if (!ok() || !data.Valid || framebufferWidth <= 0 || framebufferHeight <= 0 || data.TotalVtxCount <= 0) {
    last_ = FrameStats{};
    return;
  }
  const bool fits = cacheFits(data);
  if (cacheBroken_ || !ensureCache(framebufferWidth, framebufferHeight)) {
    cacheBroken_ = true;  // no picture to keep on this device: drawn as it is, every frame
    render(data);
    return;
  }
  last_ = FrameStats{};
  last_.vertices = static_cast<std::uint32_t>(data.TotalVtxCount);
  last_.indices = static_cast<std::uint32_t>(data.TotalIdxCount);
  last_.cached = true;
  if (redraw || !fits) {
    // Premultiplied: glBlendFuncSeparate(SRC_ALPHA, ONE_MINUS_SRC_ALPHA, ONE, ONE_MINUS_SRC_ALPHA)
    // over transparent black leaves colour x alpha in rgb and the coverage in alpha.
    const Slot& slot = upload(data);
    glBindFramebuffer(GL_FRAMEBUFFER, cacheFramebuffer_);
    glViewport(0, 0, framebufferWidth, framebufferHeight);
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    drawLists(data, framebufferWidth, framebufferHeight, slot);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    last_.redrawn = true;

    copyCorners_.clear();
    copiedPixels_ = 0;
    for (const PixelRect& r : cover) {
      if (r.empty()) continue;
      const auto x0 = static_cast<float>(r.x0), y0 = static_cast<float>(r.y0);
      const auto x1 = static_cast<float>(r.x1), y1 = static_cast<float>(r.y1);
      copyCorners_.insert(copyCorners_.end(), {x0, y0, x1, y0, x0, y1, x1, y0, x1, y1, x0, y1});
      copiedPixels_ += static_cast<std::uint64_t>(r.area());
    }
    copyVertices_ = static_cast<int>(copyCorners_.size() / 2);
    const std::size_t bytes = copyCorners_.size() * sizeof(float);
    glBindBuffer(GL_ARRAY_BUFFER, copyBuffer_);
    if (bytes > copyBytes_) {
      copyBytes_ = grownCapacity(copyBytes_, bytes);
      glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(copyBytes_), nullptr, GL_DYNAMIC_DRAW);
    }
    if (bytes > 0) glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(bytes), copyCorners_.data());
    last_.uploadBytes += bytes;
  }
  if (copyVertices_ == 0) return;
  glViewport(0, 0, framebufferWidth, framebufferHeight);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glDisable(GL_CULL_FACE);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_SCISSOR_TEST);
  glUseProgram(copyProgram_);
  glUniform2f(copySizeUniform_, static_cast<float>(framebufferWidth), static_cast<float>(framebufferHeight));
  glUniform1i(copyTextureUniform_, 0);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, cacheTexture_);
  glBindVertexArray(copyVao_);
  glDrawArrays(GL_TRIANGLES, 0, copyVertices_);
  ++last_.drawCalls;
  last_.copiedPixels = copiedPixels_;
  glBindVertexArray(0);
  glDisable(GL_BLEND);
}

}  // namespace qv
