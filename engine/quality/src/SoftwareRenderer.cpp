#include "qv/quality/SoftwareRenderer.h"

#include <array>
#include <cctype>
#include <string>

namespace qv {

bool isSoftwareRenderer(std::string_view renderer) {
  std::string lower(renderer);
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  // Names as the browsers report them, e.g. "ANGLE (Google, Vulkan 1.3.0 (SwiftShader Device
  // (Subzero) (0x0000C0DE)), SwiftShader driver)", "ANGLE (Microsoft, Microsoft Basic Render Driver
  // Direct3D11 vs_5_0 ps_5_0, D3D11)", "llvmpipe (LLVM 15.0.6, 256 bits)", Firefox's sanitized
  // "llvmpipe, or similar", "Google SwiftShader".
  static constexpr std::array<std::string_view, 6> kSoftware = {"swiftshader",         "llvmpipe", "softpipe",
                                                                "basic render driver", "software", "warp"};
  for (std::string_view word : kSoftware) {
    const std::size_t at = lower.find(word);
    if (at == std::string::npos) continue;
    // "warp" only as a word of its own: not inside another name.
    if (word == "warp") {
      const bool startOk = at == 0 || !std::isalnum(static_cast<unsigned char>(lower[at - 1]));
      const std::size_t end = at + word.size();
      const bool endOk = end == lower.size() || !std::isalnum(static_cast<unsigned char>(lower[end]));
      if (!startOk || !endOk) continue;
    }
    return true;
  }
  return false;
}

}  // namespace qv
