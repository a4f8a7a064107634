#include "Shaders.h"

namespace qv::shaders {

// Buildings. Each vertex is a footprint corner at a floor level (or a roof point) with its slot in
// the building table. Animated buildings (floorBase >= 0) move each vertex by the displacement of
// its floor, interpolated between the two floor levels around its height; walls are coloured per
// storey from the provoking (bottom-ring) vertex, so each storey shows its own drift.
const char* const kBuildingVertex = R"(#version 300 es
precision highp float;
precision highp int;
precision highp sampler2D;

layout(location = 0) in vec3 a_position;
layout(location = 1) in ivec4 a_normalKind;
layout(location = 2) in uint a_slot;

uniform mat4 u_viewProjection;
uniform vec3 u_origin;
uniform sampler2D u_buildings;
uniform sampler2D u_floors;
uniform sampler2D u_series;
uniform float u_time;  // scene time, seconds: where the drift series are read
// The colour mode (qv::ColorMode) is a constant of each program: GlRenderDevice defines
// QV_COLOR_MODE after the #version line.
const int colorMode = QV_COLOR_MODE;
uniform float u_amplitude;
uniform bool u_showModels;  // LOD2 models (kind bit kKindModel) or, instead, their extrusions (kKindFallback)

out vec3 v_normal;
out vec3 v_world;
flat out vec4 v_color;
flat out float v_hatch;

// The tables' layout (qv/scene/GpuConstants.h) and the palette (qv/scene/Palette.h), inserted by
// the device when it builds the program.
@CONSTANTS@
@PALETTE@

// The largest storey drift of a building or block at time t from its drift series (the windows'
// values at their centres, linear between them; 0 before the shaking arrives, the last window's
// after), or -1 when it has none. The C++ mirror and its tests: qv::seriesDriftAt (qv/anim/SeriesSampling.h).
float seriesDrift(BuildingRow b, float t) {
  if (b.seriesBase < 0.0 || b.seriesCount < 0.5) return -1.0;
  if (t < b.seriesStart) return 0.0;
  float last = b.seriesCount - 1.0;
  float u = clamp((t - b.seriesStart) * b.seriesRateHz - 0.5, 0.0, last);
  float i0 = floor(u);
  float a = seriesCode(u_series, int(b.seriesBase + i0));
  float c = seriesCode(u_series, int(b.seriesBase + min(i0 + 1.0, last)));
  return kSeriesFullScale * mix(a * a, c * c, u - i0);
}

// A building's sway from its drift series where its floors are not moved one by one: the roof
// moves swayGainM × drift, split evenly between X and Y, each at its first-mode period from the
// series' start; a point moves its height fraction of that. The C++ mirror and its tests:
// qv::seriesSwayAt (qv/anim/SeriesSampling.h).
vec2 seriesSway(BuildingRow b, SwayRow w, float drift, float t, float heightFraction) {
  if (drift <= 0.0 || w.swayGainM <= 0.0 || t < b.seriesStart) return vec2(0.0);
  float since = t - b.seriesStart;
  float roof = w.swayGainM * drift * clamp(heightFraction, 0.0, 1.0) * 0.70710678;
  return roof * vec2(sin(6.28318531 * since / max(w.swayPeriodXS, 0.01)), sin(6.28318531 * since / max(w.swayPeriodYS, 0.01)));
}

void main() {
  BuildingRow b = readBuilding(u_buildings, int(a_slot));
  float storeyHeight = max(b.storeyHeightMeters, 0.1);
  int storeys = max(int(b.storeys + 0.5), 1);
  int floorBase = int(b.floorBase);
  float peakValue = b.peakValue;
  float damage = b.damageState;
  uint flags = uint(b.flags + 0.5);
  float baseZ = b.baseZ;
  float lossCode = b.lossCode;  // packLossCode (qv/scene/RenderDevice.h); -1 without probabilities

  vec3 position = a_position;
  float drift = 0.0;  // the storey's drift now, for animated buildings only
  float peakStorey = peakValue;
  // The building's (or block's) largest storey drift now from its series, when its floors are not
  // moved one by one (-1 without a series).
  float seriesNow = floorBase >= 0 ? -1.0 : seriesDrift(b, u_time);
  if (floorBase < 0 && seriesNow > 0.0) {
    float height = storeyHeight * float(storeys);
    SwayRow sway = readSway(u_buildings, int(a_slot));  // its fourth texel, read only here
    position.xy += seriesSway(b, sway, seriesNow, u_time, (position.z - baseZ) / height) * u_amplitude;
  }
  if (floorBase >= 0) {
    // Skinning by height: the floors below and above the vertex, blended linearly in height (the
    // C++ mirror and its tests: qv::floorBlendAt in qv/anim/FloorBlend.h).
    float level = clamp((position.z - baseZ) / storeyHeight, 0.0, float(storeys));
    int f0 = min(int(floor(level)), storeys);
    int f1 = min(f0 + 1, storeys);
    FloorRow d0 = readFloor(u_floors, floorBase + f0);
    FloorRow d1 = readFloor(u_floors, floorBase + f1);
    position.xy += mix(vec2(d0.dxMeters, d0.dyMeters), vec2(d1.dxMeters, d1.dyMeters), level - float(f0)) * u_amplitude;
    // The storey above this vertex's level (the top ring belongs to the top storey).
    int s = min(int(floor(level + 0.01)), storeys - 1);
    FloorRow below = readFloor(u_floors, floorBase + s);
    FloorRow above = readFloor(u_floors, floorBase + s + 1);
    drift = length(vec2(above.dxMeters - below.dxMeters, above.dyMeters - below.dyMeters)) / storeyHeight;
    peakStorey = below.peakDriftAbove;
  }

  vec3 color;
  // Current drift: the warm ramp only for a drift at this moment: each storey's for the buildings
  // animated floor by floor, else the building's (or block's) largest from its drift series; those
  // without either show their peak over the whole record in grey levels, never in colours of
  // damage (Palette.h).
  if (colorMode == kModeCurrentDrift) {
    float now = floorBase >= 0 ? drift : seriesNow;
    color = now >= 0.0 ? ramp(driftPosition(now)) : notAnimatedGrey(driftPosition(peakValue));
  }
  else if (colorMode == kModePeakDrift) color = ramp(driftPosition(peakStorey));
  else if (colorMode == kModeDamageState) color = damage < kDamageNoResult + 0.5 ? kNoResult : ramp(damage / kDamageComplete);
  else if (colorMode >= kModeModerateOrWorse) {
    // Probabilistic modes: P(>= moderate), expected damage state / 4, the most likely inspection tag.
    float code = max(lossCode, 0.0);
    float tag = floor(code / kLossCodeTagFactor);
    float rest = code - tag * kLossCodeTagFactor;
    float expected = floor(rest / kLossCodeExpectedFactor);
    float moderate = rest - expected * kLossCodeExpectedFactor;
    if (colorMode == kModeModerateOrWorse) color = ramp(moderate / kLossCodeLevels);
    else if (colorMode == kModeExpectedDamage) color = ramp(expected / kLossCodeLevels);
    else color = tag < 0.5 ? kTagGreen : (tag < 1.5 ? kTagYellow : kTagRed);
  }
  else color = vec3(0.82, 0.80, 0.76);
  // Results not loaded yet (kDamagePending): plain, neither coloured nor marked as missing.
  bool pending = damage < kDamagePending + 0.5;
  if (pending) color = vec3(0.82, 0.80, 0.76);
  // No response for this building: its own colour, whatever the mode (hatched in the fragment stage).
  // (The probabilistic modes also mark results without probabilities, e.g. imported ones.)
  bool probabilistic = colorMode >= kModeModerateOrWorse;
  bool missing = damage < kDamageNoResult + 0.5 || (probabilistic && lossCode < -0.5);
  float noResult = (colorMode != kModeNeutral && missing && !pending) ? 1.0 : 0.0;
  if (noResult > 0.5) color = kNoResult;

  int kind = a_normalKind.w & kKindMask;
  bool otherLod = (a_normalKind.w & (u_showModels ? kKindFallback : kKindModel)) != 0;
  if (kind == kKindRoof) color *= 1.08;  // roofs a touch lighter than walls
  float alpha = 1.0;
  if ((flags & kFlagDimmed) != 0u) { color = mix(color, kDimmed, 0.85); noResult = 0.0; alpha = 0.0; }
  if ((flags & kFlagSelected) != 0u) { color = mix(color, kSelected, 0.65); alpha = 2.0; }
  v_color = vec4(color, alpha);
  v_hatch = noResult;

  vec3 world = position + u_origin;
  v_world = world;
  v_normal = vec3(a_normalKind.xyz) / 127.0;
  gl_Position = (flags & kFlagHidden) != 0u || otherLod ? vec4(2.0, 2.0, 2.0, 1.0) : u_viewProjection * vec4(world, 1.0);
}
)";

const char* const kBuildingFragment = R"(#version 300 es
precision highp float;

in vec3 v_normal;
in vec3 v_world;
flat in vec4 v_color;
flat in float v_hatch;

uniform vec3 u_sunDirection;
uniform vec3 u_eye;

out vec4 o_color;

void main() {
  vec3 n = normalize(v_normal);
  float sun = max(dot(n, -u_sunDirection), 0.0);
  float sky = 0.5 + 0.5 * n.z;  // hemispheric ambient: up-facing surfaces see more sky
  vec3 lit = v_color.rgb * (0.42 + 0.22 * sky + 0.55 * sun);
  // Buildings without a result: diagonal hatching in screen space, readable without colour.
  if (v_hatch > 0.5 && mod(gl_FragCoord.x + gl_FragCoord.y, 8.0) < 2.0) lit *= 0.72;
  // Selected buildings glow slightly so they stand out in shadow too.
  if (v_color.a > 1.5) lit = max(lit, v_color.rgb * 0.75);
  // Aerial perspective: far buildings fade towards the sky colour.
  float d = length(v_world - u_eye);
  float fog = 1.0 - exp(-d * 0.000035);
  o_color = vec4(mix(lit, vec3(0.80, 0.85, 0.90), fog * 0.7), 1.0);
}
)";

// Ground: one quad over the given rectangle with a faint 100 m grid for scale.
const char* const kGroundVertex = R"(#version 300 es
precision highp float;
layout(location = 0) in vec2 a_corner;
uniform mat4 u_viewProjection;
uniform vec4 u_rect;
out vec3 v_world;
void main() {
  vec2 p = mix(u_rect.xy, u_rect.zw, a_corner);
  v_world = vec3(p, -0.05);
  gl_Position = u_viewProjection * vec4(v_world, 1.0);
}
)";

const char* const kGroundFragment = R"(#version 300 es
precision highp float;
in vec3 v_world;
uniform vec3 u_eye;
out vec4 o_color;
void main() {
  vec2 cell = abs(fract(v_world.xy / 100.0 + 0.5) - 0.5) * 100.0;
  vec2 width = fwidth(v_world.xy) * 1.2;
  float line = 1.0 - min(min(cell.x / max(width.x, 1e-3), cell.y / max(width.y, 1e-3)), 1.0);
  float d = length(v_world - u_eye);
  line *= clamp(1.0 - d / 6000.0, 0.0, 1.0);
  vec3 base = vec3(0.60, 0.63, 0.60);
  vec3 color = mix(base, vec3(0.52, 0.55, 0.53), line * 0.6);
  float fog = 1.0 - exp(-d * 0.000035);
  o_color = vec4(mix(color, vec3(0.80, 0.85, 0.90), fog * 0.7), 1.0);
}
)";

// The map under the city (qv::GroundDrawItem): flat triangles coloured by their class
// (the palette's ground colours, kGroundClass, generated into the shader at @PALETTE@), muted so
// that the buildings' damage colours stay what the eye finds first.
const char* const kGroundMapVertex = R"(#version 300 es
precision highp float;
layout(location = 0) in vec2 a_position;
layout(location = 1) in uint a_class;
uniform mat4 u_viewProjection;
uniform vec3 u_origin;
out vec3 v_world;
flat out uint v_class;
void main() {
  v_world = vec3(a_position + u_origin.xy, 0.0);
  v_class = a_class;
  gl_Position = u_viewProjection * vec4(v_world, 1.0);
}
)";

const char* const kGroundMapFragment = R"(#version 300 es
precision highp float;
in vec3 v_world;
flat in uint v_class;
uniform vec3 u_eye;
out vec4 o_color;
@PALETTE@
void main() {
  vec3 color = kGroundClass[min(v_class, 9u)];
  float d = length(v_world - u_eye);
  float fog = 1.0 - exp(-d * 0.000035);
  o_color = vec4(mix(color, vec3(0.80, 0.85, 0.90), fog * 0.7), 1.0);
}
)";

// Map markers (qv::MapMarker): each a quad of two triangles around its centre, a fixed number of
// framebuffer pixels across whatever the distance; the fragment stage cuts a disc with a ring.
const char* const kMarkerVertex = R"(#version 300 es
precision highp float;
layout(location = 0) in vec3 a_center;
layout(location = 1) in vec2 a_corner;  // (-1, -1) .. (1, 1)
layout(location = 2) in vec3 a_color;
layout(location = 3) in vec2 a_radiusRing;  // radius in pixels, ring brightness (0 dark, 1 white)
uniform mat4 u_viewProjection;
uniform vec2 u_viewport;  // framebuffer pixels
out vec2 v_corner;
flat out vec3 v_color;
flat out float v_ring;
void main() {
  vec4 clip = u_viewProjection * vec4(a_center, 1.0);
  // Behind the eye: off screen.
  if (clip.w <= 0.0) { gl_Position = vec4(2.0, 2.0, 2.0, 1.0); return; }
  clip.xy += a_corner * a_radiusRing.x * 2.0 / u_viewport * clip.w;
  gl_Position = vec4(clip.xy, 0.0, clip.w);
  v_corner = a_corner;
  v_color = a_color;
  v_ring = a_radiusRing.y;
}
)";

const char* const kMarkerFragment = R"(#version 300 es
precision mediump float;
in vec2 v_corner;
flat in vec3 v_color;
flat in float v_ring;
out vec4 o_color;
void main() {
  float d = length(v_corner);
  if (d > 1.0) discard;
  vec3 ring = mix(vec3(0.08, 0.08, 0.10), vec3(1.0), v_ring);
  o_color = vec4(d > 0.68 ? ring : v_color, 1.0);
}
)";

// The panels (Dear ImGui's draw lists, drawn by GlImGuiRenderer): 2-D positions in framebuffer-
// independent display units, the font atlas's coordinates and an 8-bit RGBA colour per vertex.
const char* const kUiVertex = R"(#version 300 es
precision highp float;
layout(location = 0) in vec2 a_position;
layout(location = 1) in vec2 a_uv;
layout(location = 2) in vec4 a_color;
uniform vec4 u_display;  // x, y of the top-left corner, 2 / width, -2 / height
out vec2 v_uv;
out vec4 v_color;
void main() {
  v_uv = a_uv;
  v_color = a_color;
  gl_Position = vec4((a_position - u_display.xy) * u_display.zw + vec2(-1.0, 1.0), 0.0, 1.0);
}
)";

const char* const kUiFragment = R"(#version 300 es
precision mediump float;
uniform sampler2D u_texture;
in vec2 v_uv;
in vec4 v_color;
out vec4 o_color;
void main() {
  o_color = v_color * texture(u_texture, v_uv);
}
)";

// The panels' cached picture (GlImGuiRenderer::renderCached) copied over the framebuffer: one
// rectangle per two triangles, corners in framebuffer pixels from the top-left; the picture has the
// framebuffer's size, so each fragment samples its own pixel's centre (nearest filtering).
// Premultiplied: blend ONE, ONE_MINUS_SRC_ALPHA.
const char* const kUiCopyVertex = R"(#version 300 es
precision highp float;
layout(location = 0) in vec2 a_pixel;
uniform highp vec2 u_size;  // the framebuffer's width and height in pixels
void main() {
  gl_Position = vec4(a_pixel.x / u_size.x * 2.0 - 1.0, 1.0 - a_pixel.y / u_size.y * 2.0, 0.0, 1.0);
}
)";

const char* const kUiCopyFragment = R"(#version 300 es
precision mediump float;
uniform sampler2D u_texture;
uniform highp vec2 u_size;  // the framebuffer's width and height in pixels
out vec4 o_color;
void main() {
  highp vec2 uv = gl_FragCoord.xy / u_size;
  o_color = texture(u_texture, uv);
}
)";

}  // namespace qv::shaders
