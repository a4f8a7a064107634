#include "qv/scene/NullRenderDevice.h"

#include <algorithm>

namespace qv {

MeshHandle NullRenderDevice::createMesh(const MeshData& mesh) {
  if (mesh.indices.empty()) return {};
  const std::size_t bytes = mesh.vertices.size() * sizeof(BuildingVertex) + mesh.indices.size() * sizeof(std::uint32_t);
  const std::uint32_t id = nextId_++;
  meshes_[id] = Mesh{mesh.triangleCount(), mesh.modelTriangles, mesh.fallbackTriangles, bytes};
  pendingUpload_ += bytes;
  return MeshHandle{id};
}

MeshHandle NullRenderDevice::createGroundMesh(const GroundMeshData& mesh) {
  if (mesh.indices.empty() || mesh.vertices.empty()) return {};
  const std::size_t bytes = mesh.vertices.size_bytes() + mesh.indices.size_bytes();
  const std::uint32_t id = nextId_++;
  meshes_[id] = Mesh{mesh.indices.size() / 3, 0, 0, bytes};
  pendingUpload_ += bytes;
  return MeshHandle{id};
}

void NullRenderDevice::destroyMesh(MeshHandle mesh) {
  meshes_.erase(mesh.id);
}

std::size_t NullRenderDevice::meshTriangles(MeshHandle mesh) const {
  const auto it = meshes_.find(mesh.id);
  return it == meshes_.end() ? 0 : it->second.triangles;
}

void NullRenderDevice::writeBuildings(std::uint32_t first, std::span<const BuildingGpuRecord> records) {
  buildingRows_ = std::max(buildingRows_, static_cast<std::size_t>(first) + records.size());
  pendingUpload_ += records.size_bytes();
}

void NullRenderDevice::writeFloors(std::uint32_t first, std::span<const FloorGpuRecord> records) {
  floorRows_ = std::max(floorRows_, static_cast<std::size_t>(first) + records.size());
  pendingUpload_ += records.size_bytes();
}

void NullRenderDevice::writeSeries(std::uint32_t first, std::span<const std::uint8_t> codes) {
  seriesSamples_ = std::max(seriesSamples_, static_cast<std::size_t>(first) + codes.size());
  pendingUpload_ += codes.size_bytes();
}

void NullRenderDevice::render(const FrameUniforms& uniforms, std::span<const DrawItem> items) {
  DeviceFrameStats stats;
  stats.uploadBytes = pendingUpload_;
  pendingUpload_ = 0;
  if (!uniforms.ground.empty()) {
    stats.drawCalls += 1;
    stats.triangles += 2;
  }
  for (const GroundDrawItem& item : uniforms.groundItems) {
    const auto it = meshes_.find(item.mesh.id);
    if (it == meshes_.end()) continue;
    stats.drawCalls += 1;
    stats.triangles += it->second.triangles;
  }
  for (const DrawItem& item : items) {
    const auto it = meshes_.find(item.mesh.id);
    if (it == meshes_.end()) continue;
    if (item.spans.empty()) {
      stats.drawCalls += 1;
      stats.triangles +=
          it->second.triangles - (uniforms.showModels ? it->second.fallbackTriangles : it->second.modelTriangles);
      continue;
    }
    for (const IndexSpan& span : item.spans) {
      if (span.indexCount == 0 || std::size_t{span.firstIndex} + span.indexCount > it->second.triangles * 3) continue;
      stats.drawCalls += 1;
      stats.triangles += span.indexCount / 3 - (uniforms.showModels ? span.fallbackTriangles : span.modelTriangles);
    }
  }
  if (!uniforms.markers.empty()) {
    stats.drawCalls += 1;
    stats.triangles += 2 * uniforms.markers.size();
  }
  last_ = stats;
}

std::size_t NullRenderDevice::gpuBytes() const {
  std::size_t total = buildingRows_ * sizeof(BuildingGpuRecord) + floorRows_ * sizeof(FloorGpuRecord) + seriesSamples_;
  for (const auto& [id, mesh] : meshes_) total += mesh.bytes;
  return total;
}

}  // namespace qv
