// The WebGL2 (OpenGL ES 3.0) implementation of RenderDevice.
//
// Meshes live in one VAO + vertex buffer + index buffer each (a tile's merged geometry). The
// per-building table and the per-floor displacement table are RGBA32F data textures kGpuTableWidth
// texels wide that the vertex shader reads with texelFetch; CPU shadows let them grow and let only the
// changed rows be re-sent each frame. The series table (the drift series, one byte a sample) is an
// RGBA8 texture of the same width, four samples a texel, kept the same way. Must be created and used
// with a current WebGL2 context.
#pragma once

#include <array>
#include <string>
#include <unordered_map>
#include <vector>

#include "qv/scene/RenderDevice.h"

namespace qv {

class GlRenderDevice final : public RenderDevice {
 public:
  GlRenderDevice();
  ~GlRenderDevice() override;
  GlRenderDevice(const GlRenderDevice&) = delete;
  GlRenderDevice& operator=(const GlRenderDevice&) = delete;

  /// False when the shaders failed to compile or link; error() says why.
  [[nodiscard]] bool ok() const { return error_.empty(); }
  [[nodiscard]] const std::string& error() const { return error_; }

  MeshHandle createMesh(const MeshData& mesh) override;
  MeshHandle createGroundMesh(const GroundMeshData& mesh) override;
  void destroyMesh(MeshHandle mesh) override;
  [[nodiscard]] std::size_t meshTriangles(MeshHandle mesh) const override;
  void writeBuildings(std::uint32_t first, std::span<const BuildingGpuRecord> records) override;
  void writeFloors(std::uint32_t first, std::span<const FloorGpuRecord> records) override;
  void writeSeries(std::uint32_t first, std::span<const std::uint8_t> codes) override;
  /// kTableWidth x MAX_TEXTURE_SIZE RGBA8 texels (up to 8192 rows: 64 MB), four samples each.
  [[nodiscard]] std::uint32_t maxSeriesSamples() const override;
  void render(const FrameUniforms& uniforms, std::span<const DrawItem> items) override;
  [[nodiscard]] DeviceFrameStats lastFrameStats() const override { return last_; }
  [[nodiscard]] std::size_t gpuBytes() const override;

  /// Texels per row of both data textures (the shaders get the same number from glslConstants()).
  static constexpr int kTableWidth = kGpuTableWidth;

 private:
  struct Mesh {
    unsigned vao = 0, vertexBuffer = 0, indexBuffer = 0;
    int indexCount = 0;
    std::size_t modelTriangles = 0, fallbackTriangles = 0;  // MeshData's
    std::size_t bytes = 0;
  };
  struct DataTexture {
    unsigned texture = 0;
    int rows = 0;               // allocated rows
    std::vector<float> shadow;  // rows × kTableWidth × 4 floats
    int dirtyFirstRow = -1, dirtyLastRow = -1;
  };
  /// Uploads vertices and indices into a new VAO whose vertex layout `attributes` sets up.
  MeshHandle uploadMesh(const void* vertices, std::size_t vertexBytes, std::span<const std::uint32_t> indices,
                        void (*attributes)(), std::size_t modelTriangles, std::size_t fallbackTriangles);
  void writeTexels(DataTexture& table, std::size_t firstTexel, const float* data, std::size_t texelCount);
  void flush(DataTexture& table);
  struct ByteTexture {
    unsigned texture = 0;
    int rows = 0;                      // allocated rows
    std::vector<std::uint8_t> shadow;  // rows × kTableWidth × 4 bytes
    int dirtyFirstRow = -1, dirtyLastRow = -1;
  };
  void flush(ByteTexture& table);

  // The building program of one colour mode, and its uniforms' locations.
  struct BuildingProgram {
    unsigned program = 0;
    int viewProjection = -1, origin = -1, buildings = -1, floors = -1, series = -1, amplitude = -1, time = -1,
        sunDirection = -1, eye = -1, showModels = -1;
  };
  /// The program for `mode`, built on first use; null when it failed (error() says why). The mode
  /// is a constant in it, not a uniform: a software renderer runs every branch of an if/else
  /// chain on a uniform for every vertex, and the colour modes' chain was about a third of the
  /// vertex work.
  const BuildingProgram* buildingProgram(ColorMode mode);

  std::string error_;
  std::array<BuildingProgram, kColorModeCount> building_{};
  unsigned groundProgram_ = 0;
  unsigned groundVao_ = 0, groundBuffer_ = 0;
  DataTexture buildings_, floors_;
  ByteTexture series_;
  std::unordered_map<std::uint32_t, Mesh> meshes_;
  std::uint32_t nextId_ = 1;
  std::uint64_t pendingUpload_ = 0;
  std::size_t meshBytes_ = 0;
  DeviceFrameStats last_;
  int maxTextureSize_ = kTableWidth;

  struct GroundUniforms {
    int viewProjection = -1, rect = -1, eye = -1;
  } g_;
  // The map under the city (FrameUniforms::groundItems): one program, one draw call a mesh.
  void drawGroundItems(const FrameUniforms& uniforms, DeviceFrameStats& stats);
  unsigned groundMapProgram_ = 0;
  int groundMapViewProjection_ = -1, groundMapOrigin_ = -1, groundMapEye_ = -1;
  // Map markers: one program, one buffer rewritten each frame they are drawn.
  void drawMarkers(const FrameUniforms& uniforms, DeviceFrameStats& stats);
  unsigned markerProgram_ = 0, markerVao_ = 0, markerBuffer_ = 0;
  std::size_t markerBufferBytes_ = 0;
  int markerViewProjection_ = -1, markerViewport_ = -1;
  std::vector<float> markerVertices_;
};

}  // namespace qv
