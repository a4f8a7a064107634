#include "qv/ui/PanelPicture.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace qv::ui {
namespace {

/// Multiply-rotate mixing of 8 bytes at a time (the tail zero-padded): fast enough for the ~200 KB
/// a frame of the default panel, and any changed byte changes the key.
class KeyMixer {
 public:
  void add(const void* bytes, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(bytes);
    std::size_t i = 0;
    for (; i + 8 <= size; i += 8) {
      std::uint64_t word = 0;
      std::memcpy(&word, p + i, 8);
      mix(word);
    }
    if (i < size) {
      std::uint64_t word = 0;
      std::memcpy(&word, p + i, size - i);
      mix(word ^ (static_cast<std::uint64_t>(size - i) << 56));
    }
    mix(size);
  }
  [[nodiscard]] std::uint64_t key() const {
    std::uint64_t z = h_;  // splitmix64's finaliser
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

 private:
  void mix(std::uint64_t word) {
    h_ ^= word * 0x9E3779B97F4A7C15ull;
    h_ = ((h_ << 27) | (h_ >> 37)) * 0xFF51AFD7ED558CCDull + 0x2545F4914F6CDD1Dull;
  }
  std::uint64_t h_ = 0x6A09E667F3BCC909ull;
};

}  // namespace

std::uint64_t drawDataKey(const ImDrawData& data) {
  KeyMixer mixer;
  const float frame[] = {data.DisplayPos.x,  data.DisplayPos.y,       data.DisplaySize.x,
                         data.DisplaySize.y, data.FramebufferScale.x, data.FramebufferScale.y};
  mixer.add(frame, sizeof frame);
  for (int n = 0; n < data.CmdListsCount; ++n) {
    const ImDrawList& list = *data.CmdLists[n];
    mixer.add(list.VtxBuffer.Data, static_cast<std::size_t>(list.VtxBuffer.Size) * sizeof(ImDrawVert));
    mixer.add(list.IdxBuffer.Data, static_cast<std::size_t>(list.IdxBuffer.Size) * sizeof(ImDrawIdx));
    for (const ImDrawCmd& cmd : list.CmdBuffer) {
      const auto texture = reinterpret_cast<std::uintptr_t>(cmd.GetTexID());
      const auto callback = reinterpret_cast<std::uintptr_t>(cmd.UserCallback);
      const std::uint64_t fields[] = {cmd.VtxOffset, cmd.IdxOffset, cmd.ElemCount, texture, callback};
      mixer.add(&cmd.ClipRect, sizeof cmd.ClipRect);
      mixer.add(fields, sizeof fields);
    }
  }
  return mixer.key();
}

std::vector<PixelRect> panelRects(const ImDrawData& data) {
  std::vector<PixelRect> rects;
  const ImVec2 offset = data.DisplayPos;
  const ImVec2 scale = data.FramebufferScale;
  for (int n = 0; n < data.CmdListsCount; ++n) {
    const ImDrawList& list = *data.CmdLists[n];
    if (list.VtxBuffer.Size == 0 || list.IdxBuffer.Size == 0) continue;
    ImVec2 lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
    for (const ImDrawVert& v : list.VtxBuffer) {
      lo = ImVec2(std::min(lo.x, v.pos.x), std::min(lo.y, v.pos.y));
      hi = ImVec2(std::max(hi.x, v.pos.x), std::max(hi.y, v.pos.y));
    }
    ImVec4 clip(INFINITY, INFINITY, -INFINITY, -INFINITY);
    for (const ImDrawCmd& cmd : list.CmdBuffer) {
      if (cmd.UserCallback != nullptr || cmd.ElemCount == 0) continue;
      clip = ImVec4(std::min(clip.x, cmd.ClipRect.x), std::min(clip.y, cmd.ClipRect.y),
                    std::max(clip.z, cmd.ClipRect.z), std::max(clip.w, cmd.ClipRect.w));
    }
    const float x0 = (std::max(lo.x, clip.x) - offset.x) * scale.x;
    const float y0 = (std::max(lo.y, clip.y) - offset.y) * scale.y;
    const float x1 = (std::min(hi.x, clip.z) - offset.x) * scale.x;
    const float y1 = (std::min(hi.y, clip.w) - offset.y) * scale.y;
    if (!(x1 > x0 && y1 > y0)) continue;
    // Clamped so that a huge or non-finite coordinate cannot overflow int.
    auto pixel = [](float v) { return static_cast<int>(std::clamp(v, -1.0e6f, 1.0e6f)); };
    rects.push_back({pixel(std::floor(x0)), pixel(std::floor(y0)), pixel(std::ceil(x1)), pixel(std::ceil(y1))});
  }
  return rects;
}

}  // namespace qv::ui
