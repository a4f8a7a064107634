// Recognising a software WebGL renderer: the browser draws on the CPU (no GPU, a virtual desktop,
// a blocked driver), where the frame time is the triangle count and the antialiased pixels, so the
// viewer starts in its weak-device preset there.
#pragma once

#include <string_view>

namespace qv {

/// True when `renderer` (WebGL's UNMASKED_RENDERER_WEBGL, or RENDERER when that is unavailable)
/// names a software rasterizer: SwiftShader (Chromium, ANGLE), WARP and "Microsoft Basic Render
/// Driver" (Windows), llvmpipe and softpipe (Mesa, Firefox on Linux), or any name containing the
/// word "software". Case-insensitive. An empty or unknown name (a masked one such as "WebKit
/// WebGL") is not software: the viewer then starts at full quality and the frame-time governor
/// takes over.
[[nodiscard]] bool isSoftwareRenderer(std::string_view renderer);

}  // namespace qv
