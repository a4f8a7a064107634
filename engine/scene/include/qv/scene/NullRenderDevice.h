// A RenderDevice that keeps no GPU state and draws nothing, but accounts for everything a real
// device would be asked to do (draw calls, triangles, bytes uploaded). Used by tests and by the
// engine benchmarks under node.
#pragma once

#include <unordered_map>

#include "qv/scene/RenderDevice.h"

namespace qv {

class NullRenderDevice final : public RenderDevice {
 public:
  MeshHandle createMesh(const MeshData& mesh) override;
  MeshHandle createGroundMesh(const GroundMeshData& mesh) override;
  void destroyMesh(MeshHandle mesh) override;
  [[nodiscard]] std::size_t meshTriangles(MeshHandle mesh) const override;
  void writeBuildings(std::uint32_t first, std::span<const BuildingGpuRecord> records) override;
  void writeFloors(std::uint32_t first, std::span<const FloorGpuRecord> records) override;
  void writeSeries(std::uint32_t first, std::span<const std::uint8_t> codes) override;
  /// As a device with 8192-row textures (most GPUs and the software renderers: 64 MB).
  [[nodiscard]] std::uint32_t maxSeriesSamples() const override { return 1u << 26; }
  void render(const FrameUniforms& uniforms, std::span<const DrawItem> items) override;
  [[nodiscard]] DeviceFrameStats lastFrameStats() const override { return last_; }
  [[nodiscard]] std::size_t gpuBytes() const override;

  [[nodiscard]] std::size_t meshCount() const { return meshes_.size(); }

 private:
  struct Mesh {
    std::size_t triangles = 0;
    std::size_t modelTriangles = 0, fallbackTriangles = 0;  // MeshData's
    std::size_t bytes = 0;
  };
  std::unordered_map<std::uint32_t, Mesh> meshes_;
  std::uint32_t nextId_ = 1;
  std::size_t buildingRows_ = 0;
  std::size_t floorRows_ = 0;
  std::size_t seriesSamples_ = 0;
  std::uint64_t pendingUpload_ = 0;
  DeviceFrameStats last_;
};

}  // namespace qv
