// The boundary between the pure scene code and a graphics backend (the WebGL2 device in
// engine::render, or the null device here for tests and benchmarks without a GPU).
//
// The device owns GPU resources behind small typed handles. A handle whose creation failed is
// invalid (id 0) and drawing it is a no-op. All calls come from the frame loop's thread.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "qv/geometry/Bounds.h"
#include "qv/geometry/BuildingMesh.h"

namespace qv {

struct MeshHandle {
  std::uint32_t id = 0;
  explicit operator bool() const { return id != 0; }
  friend bool operator==(MeshHandle, MeshHandle) = default;
};

/// Texels per row of both data textures (the building and the floor table): texel i sits at
/// (i mod kGpuTableWidth, i div kGpuTableWidth). The shaders get it from glslConstants().
inline constexpr int kGpuTableWidth = 2048;
/// Bytes of one RGBA32F texel of the data textures.
inline constexpr int kGpuTexelBytes = 16;

/// Per-building row of the GPU building table (three RGBA32F texels). Slots index this table.
struct BuildingGpuRecord {
  float storeyHeightMeters = 3.0f;  ///< height of one storey (floor level k sits at baseZ + k × this)
  float storeys = 1.0f;             ///< number of storeys
  float floorBase = -1.0f;          ///< first texel of its floor rows, -1 when not animated
  float peakValue = 0.0f;           ///< peak drift ratio (colour when static)
  float damageState = -1.0f;        ///< 0..4 none..complete, -1 no result, -2 result not loaded yet
  float flags = 0.0f;               ///< BuildingFlag bits
  float baseZ = 0.0f;               ///< height of floor level 0 (the building's min height), metres
  float lossCode = -1.0f;           ///< packLossCode of its HAZUS probabilities, -1 without them
  /// Its drift series (qv::DriftSeries) in the series table: the first sample's index, -1 without
  /// one; the scene time of window 0; the number of windows; windows per second. The vertex shader
  /// reads the largest storey drift at the current time from it (kSeriesFullScale at code 255).
  float seriesBase = -1.0f;
  float seriesStart = 0.0f;
  float seriesCount = 0.0f;
  float seriesRateHz = 0.0f;
  /// Its sway where it is not moved floor by floor (qv::seriesSwayAt): the roof's displacement
  /// per unit of drift from its series (metres; its peak roof displacement over its peak storey
  /// drift, 0 for blocks and buildings without a result), and its first-mode periods in X and Y
  /// (seconds, > 0).
  float swayGainM = 0.0f;
  float swayPeriodXS = 1.0f;
  float swayPeriodYS = 1.0f;
  float reserved = 0.0f;
};
static_assert(sizeof(BuildingGpuRecord) == 64);
/// Texels per building: slot s occupies texels [s × kBuildingTexels, (s + 1) × kBuildingTexels).
inline constexpr int kBuildingTexels = static_cast<int>(sizeof(BuildingGpuRecord)) / kGpuTexelBytes;

/// BuildingGpuRecord::damageState of the top of the damage ramp (complete damage), of a building
/// without a result and of one whose results are not loaded yet.
inline constexpr float kDamageComplete = 4.0f;
inline constexpr float kDamageNoResult = -1.0f;
inline constexpr float kDamagePending = -2.0f;

enum BuildingFlag : unsigned { kFlagSelected = 1u, kFlagDimmed = 2u, kFlagHidden = 4u };

/// Per-floor row of an animated building (one RGBA32F texel): displacement of floor level k
/// (k = 0 ground .. storeys roof) in metres as simulated (the shader applies the amplitude
/// exaggeration to positions only, so colours show true drift), and the peak drift ratio of
/// storey k+1 (the storey above that level).
struct FloorGpuRecord {
  float dxMeters = 0.0f;
  float dyMeters = 0.0f;
  float peakDriftAbove = 0.0f;
  float reserved = 0.0f;
};
static_assert(sizeof(FloorGpuRecord) == 16);

/// The series table: one byte a sample (the quantized drift codes of qv::DriftSeries, on the
/// square-root scale of driftSeriesCode with this full scale), four samples a texel of an RGBA8
/// texture kGpuTableWidth texels wide: sample i is component i mod 4 of texel i div 4.
inline constexpr float kSeriesFullScale = 0.05f;
inline constexpr int kSeriesSamplesPerTexel = 4;

/// The colour modes; values are stable (the page's URL and `setColorMode` use them).
enum class ColorMode : int {
  CurrentDrift = 0,
  PeakDrift = 1,
  DamageState = 2,  ///< the deterministic state from the (median) peak drift
  Neutral = 3,
  ModerateOrWorse = 4,  ///< P(damage state >= moderate), HAZUS fragility
  ExpectedDamage = 5,   ///< expected damage state, 0 .. 4
  InspectionTag = 6,    ///< the most likely inspection tag (green, yellow, red)
};
inline constexpr int kColorModeCount = 7;

/// The packing of packLossCode: each fraction quantized to 0 … kLossCodeLevels, the expected
/// state's field and the tag's field scaled by these factors.
inline constexpr int kLossCodeLevels = 255;
inline constexpr int kLossCodeExpectedFactor = 256;
inline constexpr int kLossCodeTagFactor = 65536;

/// The HAZUS probabilities of a building packed into one float of the building table, exactly
/// representable (< 2^24): round(255 P(DS >= moderate)) + 256 round(255 E[DS] / 4) + 65536 tag, with
/// tag the most likely of green (0), yellow (1), red (2). The shader unpacks it for modes 4 to 6.
inline float packLossCode(float moderateOrWorse, float expectedState, int mostLikelyTag) {
  auto quantize = [](float x) {
    const float c = x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x);
    return static_cast<int>(c * static_cast<float>(kLossCodeLevels) + 0.5f);
  };
  const int tag = mostLikelyTag < 0 ? 0 : (mostLikelyTag > 2 ? 2 : mostLikelyTag);
  return static_cast<float>(quantize(moderateOrWorse) +
                            kLossCodeExpectedFactor * quantize(expectedState / kDamageComplete) +
                            kLossCodeTagFactor * tag);
}

/// A marker over the city: a disc of a fixed size on screen whatever the distance, so that a
/// critical facility kept by a filter, or the selected building, can be pointed at from any view.
/// Centred at `position` (city frame, metres; its roof), `radiusPixels` framebuffer pixels, filled
/// with `color` inside a dark ring (a white one when `selected`); drawn after the buildings,
/// without the depth test.
struct MapMarker {
  glm::vec3 position{0.0f};
  float radiusPixels = 8.0f;
  glm::vec3 color{1.0f};
  bool selected = false;
};

/// A ground mesh (the map under the city: qv/format/GroundTile.h): flat triangles at z = 0, each
/// vertex with the class (GroundClass, 0 .. 9) that picks its colour. Positions are relative to
/// the DrawItem's origin.
struct GroundVertex {
  float x = 0.0f, y = 0.0f;
  std::uint8_t groundClass = 0;
  std::uint8_t pad[3] = {0, 0, 0};
};
static_assert(sizeof(GroundVertex) == 12);

struct GroundMeshData {
  std::span<const GroundVertex> vertices;
  std::span<const std::uint32_t> indices;  ///< 3 per triangle, drawn in this order (painter's order)
};

/// A ground mesh to draw at `origin` (its cell's corner in the city frame).
struct GroundDrawItem {
  MeshHandle mesh;
  glm::vec3 origin{0.0f};
};

struct FrameUniforms {
  glm::mat4 viewProjection{1.0f};
  glm::vec3 eye{0.0f};
  glm::vec3 sunDirection{-0.4f, -0.6f, -0.7f};  ///< direction the light travels (towards ground)
  ColorMode colorMode = ColorMode::CurrentDrift;
  float amplitude = 1.0f;    ///< exaggeration applied to displayed displacements
  float timeSeconds = 0.0f;  ///< scene time the drift series are read at
  int viewportWidth = 1;
  int viewportHeight = 1;
  Rect ground;             ///< ground plane extent (empty: no ground)
  bool showModels = true;  ///< LOD2 models drawn (kKindModel vertices), else their LOD1 extrusions (kKindFallback)
  std::span<const MapMarker> markers;  ///< drawn last (two triangles and one draw call for all)
  /// The map under the city, drawn over the plain ground and under everything else, in order and
  /// without the depth test (each mesh is already in drawing order; meshes do not overlap).
  std::span<const GroundDrawItem> groundItems;
};

/// A run of a mesh's indices, [firstIndex, firstIndex + indexCount), with how many of its
/// triangles are LOD2 models (kKindModel) and how many their LOD1 fallbacks (kKindFallback), so
/// that the device counts only the triangles it shows.
struct IndexSpan {
  std::uint32_t firstIndex = 0;
  std::uint32_t indexCount = 0;
  std::uint32_t modelTriangles = 0;
  std::uint32_t fallbackTriangles = 0;
};

struct DrawItem {
  MeshHandle mesh;
  glm::vec3 origin{0.0f};  ///< added to the mesh's positions (tile origin in the city frame)
  /// The parts of the mesh to draw (the culling's visible buildings, merged into few runs); empty:
  /// the whole mesh. Points into storage the scene keeps until its next update.
  std::span<const IndexSpan> spans;
};

struct DeviceFrameStats {
  std::uint32_t drawCalls = 0;
  std::uint64_t triangles = 0;    ///< drawn and shown (the hidden LOD's triangles are not counted)
  std::uint64_t uploadBytes = 0;  ///< bytes sent to the GPU since the previous frame
};

class RenderDevice {
 public:
  virtual ~RenderDevice() = default;

  /// Uploads a mesh; invalid handle when it cannot (out of memory, empty mesh).
  virtual MeshHandle createMesh(const MeshData& mesh) = 0;
  /// Uploads a ground mesh (drawn through FrameUniforms::groundItems); destroyed with destroyMesh.
  /// Invalid handle when it cannot, or the device draws no ground.
  virtual MeshHandle createGroundMesh(const GroundMeshData& mesh) {
    (void)mesh;
    return {};
  }
  virtual void destroyMesh(MeshHandle mesh) = 0;
  [[nodiscard]] virtual std::size_t meshTriangles(MeshHandle mesh) const = 0;

  /// Writes rows [first, first + records.size()) of the building table, growing it as needed.
  virtual void writeBuildings(std::uint32_t first, std::span<const BuildingGpuRecord> records) = 0;
  /// Writes texels [first, first + records.size()) of the floor table, growing it as needed.
  virtual void writeFloors(std::uint32_t first, std::span<const FloorGpuRecord> records) = 0;
  /// Writes samples [first, first + codes.size()) of the series table, growing it as needed.
  virtual void writeSeries(std::uint32_t first, std::span<const std::uint8_t> codes) = 0;
  /// How many series samples the device's table can hold (the 2048 x 2048 texels every WebGL2
  /// device has, four samples each, unless the device says more).
  [[nodiscard]] virtual std::uint32_t maxSeriesSamples() const { return 1u << 24; }

  /// Draws one frame: clears, draws the ground and the items. Resets the frame statistics.
  virtual void render(const FrameUniforms& uniforms, std::span<const DrawItem> items) = 0;

  [[nodiscard]] virtual DeviceFrameStats lastFrameStats() const = 0;
  /// Bytes of GPU memory held by meshes and tables.
  [[nodiscard]] virtual std::size_t gpuBytes() const = 0;
};

}  // namespace qv
