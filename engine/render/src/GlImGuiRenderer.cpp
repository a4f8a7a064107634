#include "qv/render/GlImGuiRenderer.h"

#include <GLES3/gl3.h>
#include <imgui.h>

#include <cstddef>
#include <cstring>

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

void GlImGuiRenderer::render(const ImDrawData& data) {
  last_ = FrameStats{};
  const int framebufferWidth = static_cast<int>(data.DisplaySize.x * data.FramebufferScale.x);
  const int framebufferHeight = static_cast<int>(data.DisplaySize.y * data.FramebufferScale.y);
  if (!ok() || !data.Valid || framebufferWidth <= 0 || framebufferHeight <= 0 || data.TotalVtxCount <= 0) return;

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
  last_.vertices = static_cast<std::uint32_t>(data.TotalVtxCount);
  last_.indices = static_cast<std::uint32_t>(data.TotalIdxCount);
  last_.uploadBytes = vertexBytes + indexBytes;

  setUpState(data, framebufferWidth, framebufferHeight, slot);
  const ImVec2 clipOffset = data.DisplayPos;
  const ImVec2 clipScale = data.FramebufferScale;
  unsigned boundTexture = ~0u;
  indexBase = 0;
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

}  // namespace qv
