#include "qv/render/GlRenderDevice.h"

#include <GLES3/gl3.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>

#include "Shaders.h"
#include "qv/scene/GpuConstants.h"
#include "qv/scene/Palette.h"

namespace qv {
namespace {

void* byteOffset(std::size_t offset) {
  return reinterpret_cast<void*>(offset);  // NOLINT(performance-no-int-to-ptr): GL's offset convention
}

}  // namespace

namespace {

// A shader source with its generated blocks: the tables' layout and the palette (qv::paletteGlsl).
std::string withGeneratedGlsl(const char* source) {
  std::string s = withGlslConstants(source);
  const auto at = s.find("@PALETTE@");
  if (at != std::string::npos) s.replace(at, 9, paletteGlsl());
  return s;
}

}  // namespace

const GlRenderDevice::BuildingProgram* GlRenderDevice::buildingProgram(ColorMode mode) {
  const auto index = static_cast<std::size_t>(mode);
  if (index >= building_.size()) return nullptr;
  BuildingProgram& b = building_[index];
  if (b.program != 0) return &b;
  if (!ok()) return nullptr;
  // The mode is a constant of the program (QV_COLOR_MODE after the #version line).
  std::string vertex = withGeneratedGlsl(shaders::kBuildingVertex);
  const auto line = vertex.find('\n');
  if (line == std::string::npos) return nullptr;
  vertex.insert(line + 1, "#define QV_COLOR_MODE " + std::to_string(static_cast<int>(mode)) + "\n");
  b.program = shaders::linkProgram(vertex.c_str(), shaders::kBuildingFragment, error_);
  if (b.program == 0) return nullptr;
  const auto p = b.program;
  b.viewProjection = glGetUniformLocation(p, "u_viewProjection");
  b.origin = glGetUniformLocation(p, "u_origin");
  b.buildings = glGetUniformLocation(p, "u_buildings");
  b.floors = glGetUniformLocation(p, "u_floors");
  b.series = glGetUniformLocation(p, "u_series");
  b.time = glGetUniformLocation(p, "u_time");
  b.amplitude = glGetUniformLocation(p, "u_amplitude");
  b.sunDirection = glGetUniformLocation(p, "u_sunDirection");
  b.eye = glGetUniformLocation(p, "u_eye");
  b.showModels = glGetUniformLocation(p, "u_showModels");
  return &b;
}

GlRenderDevice::GlRenderDevice() {
  // The default mode's program now (an error shows at start); the others when first drawn.
  if (buildingProgram(ColorMode::CurrentDrift) != nullptr) {
    groundProgram_ = shaders::linkProgram(shaders::kGroundVertex, shaders::kGroundFragment, error_);
  }
  if (!ok()) return;

  markerProgram_ = shaders::linkProgram(shaders::kMarkerVertex, shaders::kMarkerFragment, error_);
  if (!ok()) return;
  markerViewProjection_ = glGetUniformLocation(markerProgram_, "u_viewProjection");
  markerViewport_ = glGetUniformLocation(markerProgram_, "u_viewport");
  glGenVertexArrays(1, &markerVao_);
  glGenBuffers(1, &markerBuffer_);

  groundMapProgram_ =
      shaders::linkProgram(shaders::kGroundMapVertex, withGeneratedGlsl(shaders::kGroundMapFragment).c_str(), error_);
  if (!ok()) return;
  groundMapViewProjection_ = glGetUniformLocation(groundMapProgram_, "u_viewProjection");
  groundMapOrigin_ = glGetUniformLocation(groundMapProgram_, "u_origin");
  groundMapEye_ = glGetUniformLocation(groundMapProgram_, "u_eye");

  g_.viewProjection = glGetUniformLocation(groundProgram_, "u_viewProjection");
  g_.rect = glGetUniformLocation(groundProgram_, "u_rect");
  g_.eye = glGetUniformLocation(groundProgram_, "u_eye");

  GLint maxSize = kTableWidth;  // WebGL2 guarantees at least 2048
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  maxTextureSize_ = maxSize;

  const float corners[] = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
  glGenVertexArrays(1, &groundVao_);
  glBindVertexArray(groundVao_);
  glGenBuffers(1, &groundBuffer_);
  glBindBuffer(GL_ARRAY_BUFFER, groundBuffer_);
  glBufferData(GL_ARRAY_BUFFER, sizeof corners, corners, GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindVertexArray(0);

  for (unsigned* texture : {&buildings_.texture, &floors_.texture, &series_.texture}) {
    glGenTextures(1, texture);
    glBindTexture(GL_TEXTURE_2D, *texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
}

GlRenderDevice::~GlRenderDevice() {
  for (auto& [id, mesh] : meshes_) {
    glDeleteVertexArrays(1, &mesh.vao);
    glDeleteBuffers(1, &mesh.vertexBuffer);
    glDeleteBuffers(1, &mesh.indexBuffer);
  }
  glDeleteTextures(1, &buildings_.texture);
  glDeleteTextures(1, &floors_.texture);
  glDeleteTextures(1, &series_.texture);
  glDeleteVertexArrays(1, &groundVao_);
  glDeleteBuffers(1, &groundBuffer_);
  glDeleteVertexArrays(1, &markerVao_);
  glDeleteBuffers(1, &markerBuffer_);
  if (markerProgram_ != 0) glDeleteProgram(markerProgram_);
  if (groundMapProgram_ != 0) glDeleteProgram(groundMapProgram_);
  for (const BuildingProgram& b : building_) {
    if (b.program != 0) glDeleteProgram(b.program);
  }
  glDeleteProgram(groundProgram_);
}

MeshHandle GlRenderDevice::uploadMesh(const void* vertices, std::size_t vertexBytes,
                                      std::span<const std::uint32_t> indices, void (*attributes)(),
                                      std::size_t modelTriangles, std::size_t fallbackTriangles) {
  Mesh mesh;
  glGenVertexArrays(1, &mesh.vao);
  glBindVertexArray(mesh.vao);
  glGenBuffers(1, &mesh.vertexBuffer);
  glBindBuffer(GL_ARRAY_BUFFER, mesh.vertexBuffer);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertexBytes), vertices, GL_STATIC_DRAW);
  attributes();
  glGenBuffers(1, &mesh.indexBuffer);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh.indexBuffer);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size_bytes()), indices.data(), GL_STATIC_DRAW);
  glBindVertexArray(0);
  if (glGetError() == GL_OUT_OF_MEMORY) {
    glDeleteVertexArrays(1, &mesh.vao);
    glDeleteBuffers(1, &mesh.vertexBuffer);
    glDeleteBuffers(1, &mesh.indexBuffer);
    return {};
  }
  mesh.indexCount = static_cast<int>(indices.size());
  mesh.modelTriangles = modelTriangles;
  mesh.fallbackTriangles = fallbackTriangles;
  mesh.bytes = vertexBytes + indices.size_bytes();
  meshBytes_ += mesh.bytes;
  pendingUpload_ += mesh.bytes;
  const std::uint32_t id = nextId_++;
  meshes_.emplace(id, mesh);
  return MeshHandle{id};
}

MeshHandle GlRenderDevice::createMesh(const MeshData& data) {
  if (!ok() || data.indices.empty() || data.vertices.empty()) return {};
  const auto attributes = [] {
    constexpr auto stride = static_cast<GLsizei>(sizeof(BuildingVertex));
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, byteOffset(offsetof(BuildingVertex, x)));
    glEnableVertexAttribArray(1);
    glVertexAttribIPointer(1, 4, GL_BYTE, stride, byteOffset(offsetof(BuildingVertex, nx)));
    glEnableVertexAttribArray(2);
    glVertexAttribIPointer(2, 1, GL_UNSIGNED_INT, stride, byteOffset(offsetof(BuildingVertex, slot)));
  };
  return uploadMesh(data.vertices.data(), data.vertices.size() * sizeof(BuildingVertex), data.indices, attributes,
                    data.modelTriangles, data.fallbackTriangles);
}

MeshHandle GlRenderDevice::createGroundMesh(const GroundMeshData& data) {
  if (!ok() || data.indices.empty() || data.vertices.empty()) return {};
  const auto attributes = [] {
    constexpr auto stride = static_cast<GLsizei>(sizeof(GroundVertex));
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride, byteOffset(offsetof(GroundVertex, x)));
    glEnableVertexAttribArray(1);
    glVertexAttribIPointer(1, 1, GL_UNSIGNED_BYTE, stride, byteOffset(offsetof(GroundVertex, groundClass)));
  };
  return uploadMesh(data.vertices.data(), data.vertices.size_bytes(), data.indices, attributes, 0, 0);
}

void GlRenderDevice::drawGroundItems(const FrameUniforms& f, DeviceFrameStats& stats) {
  if (!ok() || f.groundItems.empty()) return;
  // Painter's order: each mesh's triangles are in drawing order and meshes do not overlap, so
  // neither the depth test nor depth writes are needed; the buildings then draw over the map.
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glUseProgram(groundMapProgram_);
  glUniformMatrix4fv(groundMapViewProjection_, 1, GL_FALSE, &f.viewProjection[0][0]);
  glUniform3f(groundMapEye_, f.eye.x, f.eye.y, f.eye.z);
  for (const GroundDrawItem& item : f.groundItems) {
    const auto it = meshes_.find(item.mesh.id);
    if (it == meshes_.end()) continue;
    glUniform3f(groundMapOrigin_, item.origin.x, item.origin.y, item.origin.z);
    glBindVertexArray(it->second.vao);
    glDrawElements(GL_TRIANGLES, it->second.indexCount, GL_UNSIGNED_INT, nullptr);
    stats.drawCalls += 1;
    stats.triangles += static_cast<std::uint64_t>(it->second.indexCount / 3);
  }
  glBindVertexArray(0);
  glDepthMask(GL_TRUE);
  glEnable(GL_DEPTH_TEST);
}

void GlRenderDevice::destroyMesh(MeshHandle handle) {
  const auto it = meshes_.find(handle.id);
  if (it == meshes_.end()) return;
  glDeleteVertexArrays(1, &it->second.vao);
  glDeleteBuffers(1, &it->second.vertexBuffer);
  glDeleteBuffers(1, &it->second.indexBuffer);
  meshBytes_ -= it->second.bytes;
  meshes_.erase(it);
}

std::size_t GlRenderDevice::meshTriangles(MeshHandle handle) const {
  const auto it = meshes_.find(handle.id);
  return it == meshes_.end() ? 0 : static_cast<std::size_t>(it->second.indexCount / 3);
}

void GlRenderDevice::writeTexels(DataTexture& table, std::size_t firstTexel, const float* data,
                                 std::size_t texelCount) {
  if (texelCount == 0) return;
  const std::size_t endTexel = firstTexel + texelCount;
  const auto neededRows = static_cast<int>((endTexel + kTableWidth - 1) / kTableWidth);
  if (neededRows > maxTextureSize_) return;  // beyond the device: the caller's budget prevents this
  if (neededRows > table.rows) {
    // Grow by doubling; the whole shadow is re-sent into the new storage at the next flush.
    int rows = std::max(table.rows, 8);
    while (rows < neededRows) rows *= 2;
    rows = std::min(rows, maxTextureSize_);
    table.shadow.resize(static_cast<std::size_t>(rows) * kTableWidth * 4, 0.0f);
    glBindTexture(GL_TEXTURE_2D, table.texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kTableWidth, rows, 0, GL_RGBA, GL_FLOAT, nullptr);
    table.dirtyFirstRow = 0;
    table.dirtyLastRow = rows - 1;
    table.rows = rows;
  }
  std::memcpy(table.shadow.data() + firstTexel * 4, data, texelCount * 4 * sizeof(float));
  const auto firstRow = static_cast<int>(firstTexel / kTableWidth);
  const auto lastRow = static_cast<int>((endTexel - 1) / kTableWidth);
  table.dirtyFirstRow = table.dirtyFirstRow < 0 ? firstRow : std::min(table.dirtyFirstRow, firstRow);
  table.dirtyLastRow = std::max(table.dirtyLastRow, lastRow);
}

void GlRenderDevice::flush(DataTexture& table) {
  if (table.dirtyFirstRow < 0) return;
  const int rows = table.dirtyLastRow - table.dirtyFirstRow + 1;
  glBindTexture(GL_TEXTURE_2D, table.texture);
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, table.dirtyFirstRow, kTableWidth, rows, GL_RGBA, GL_FLOAT,
                  table.shadow.data() + static_cast<std::size_t>(table.dirtyFirstRow) * kTableWidth * 4);
  pendingUpload_ += static_cast<std::uint64_t>(rows) * kTableWidth * 16;
  table.dirtyFirstRow = table.dirtyLastRow = -1;
}

void GlRenderDevice::writeBuildings(std::uint32_t first, std::span<const BuildingGpuRecord> records) {
  writeTexels(buildings_, static_cast<std::size_t>(first) * kBuildingTexels,
              reinterpret_cast<const float*>(records.data()), records.size() * kBuildingTexels);
}

void GlRenderDevice::writeSeries(std::uint32_t first, std::span<const std::uint8_t> codes) {
  if (codes.empty()) return;
  constexpr std::size_t rowBytes = static_cast<std::size_t>(kTableWidth) * 4;
  const std::size_t end = static_cast<std::size_t>(first) + codes.size();
  const auto neededRows = static_cast<int>((end + rowBytes - 1) / rowBytes);
  if (neededRows > maxTextureSize_) return;  // beyond the device: the table's capacity prevents this
  ByteTexture& t = series_;
  if (neededRows > t.rows) {
    int rows = std::max(t.rows, 8);
    while (rows < neededRows) rows *= 2;
    rows = std::min(rows, maxTextureSize_);
    t.shadow.resize(static_cast<std::size_t>(rows) * rowBytes, 0);
    glBindTexture(GL_TEXTURE_2D, t.texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, kTableWidth, rows, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    t.dirtyFirstRow = 0;
    t.dirtyLastRow = rows - 1;
    t.rows = rows;
  }
  std::memcpy(t.shadow.data() + first, codes.data(), codes.size());
  const auto firstRow = static_cast<int>(first / rowBytes);
  const auto lastRow = static_cast<int>((end - 1) / rowBytes);
  t.dirtyFirstRow = t.dirtyFirstRow < 0 ? firstRow : std::min(t.dirtyFirstRow, firstRow);
  t.dirtyLastRow = std::max(t.dirtyLastRow, lastRow);
}

std::uint32_t GlRenderDevice::maxSeriesSamples() const {
  const auto rows = static_cast<std::uint32_t>(std::clamp(maxTextureSize_, 1, 8192));
  return static_cast<std::uint32_t>(kTableWidth) * 4u * rows;
}

void GlRenderDevice::flush(ByteTexture& t) {
  if (t.dirtyFirstRow < 0) return;
  const int rows = t.dirtyLastRow - t.dirtyFirstRow + 1;
  constexpr std::size_t rowBytes = static_cast<std::size_t>(kTableWidth) * 4;
  glBindTexture(GL_TEXTURE_2D, t.texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, t.dirtyFirstRow, kTableWidth, rows, GL_RGBA, GL_UNSIGNED_BYTE,
                  t.shadow.data() + static_cast<std::size_t>(t.dirtyFirstRow) * rowBytes);
  pendingUpload_ += static_cast<std::uint64_t>(rows) * rowBytes;
  t.dirtyFirstRow = t.dirtyLastRow = -1;
}

void GlRenderDevice::writeFloors(std::uint32_t first, std::span<const FloorGpuRecord> records) {
  writeTexels(floors_, first, reinterpret_cast<const float*>(records.data()), records.size());
}

void GlRenderDevice::render(const FrameUniforms& f, std::span<const DrawItem> items) {
  DeviceFrameStats stats;
  flush(buildings_);
  flush(floors_);
  flush(series_);
  stats.uploadBytes = pendingUpload_;
  pendingUpload_ = 0;

  glViewport(0, 0, f.viewportWidth, f.viewportHeight);
  glClearColor(0.80f, 0.85f, 0.90f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_CULL_FACE);

  if (ok() && !f.ground.empty()) {
    glUseProgram(groundProgram_);
    glUniformMatrix4fv(g_.viewProjection, 1, GL_FALSE, &f.viewProjection[0][0]);
    glUniform4f(g_.rect, f.ground.minX, f.ground.minY, f.ground.maxX, f.ground.maxY);
    glUniform3f(g_.eye, f.eye.x, f.eye.y, f.eye.z);
    glBindVertexArray(groundVao_);
    glDrawArrays(GL_TRIANGLES, 0, 6);
    stats.drawCalls += 1;
    stats.triangles += 2;
  }
  drawGroundItems(f, stats);

  const BuildingProgram* program = ok() && !items.empty() ? buildingProgram(f.colorMode) : nullptr;
  if (program != nullptr && buildings_.rows > 0) {
    const BuildingProgram& u = *program;
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glUseProgram(u.program);
    glUniformMatrix4fv(u.viewProjection, 1, GL_FALSE, &f.viewProjection[0][0]);
    glUniform1f(u.amplitude, f.amplitude);
    glUniform3f(u.sunDirection, f.sunDirection.x, f.sunDirection.y, f.sunDirection.z);
    glUniform3f(u.eye, f.eye.x, f.eye.y, f.eye.z);
    glUniform1i(u.showModels, f.showModels ? 1 : 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, buildings_.texture);
    glUniform1i(u.buildings, 0);
    glActiveTexture(GL_TEXTURE1);
    // An empty floor table still needs storage for texelFetch to be defined.
    if (floors_.rows == 0) {
      const FloorGpuRecord zero;
      writeFloors(0, std::span<const FloorGpuRecord>(&zero, 1));
      flush(floors_);
    }
    glBindTexture(GL_TEXTURE_2D, floors_.texture);
    glUniform1i(u.floors, 1);
    glActiveTexture(GL_TEXTURE2);
    // An empty series table likewise.
    if (series_.rows == 0) {
      const std::uint8_t zero[4] = {0, 0, 0, 0};
      writeSeries(0, zero);
      flush(series_);
    }
    glBindTexture(GL_TEXTURE_2D, series_.texture);
    glUniform1i(u.series, 2);
    glUniform1f(u.time, f.timeSeconds);
    for (const DrawItem& item : items) {
      const auto it = meshes_.find(item.mesh.id);
      if (it == meshes_.end()) continue;
      glUniform3f(u.origin, item.origin.x, item.origin.y, item.origin.z);
      glBindVertexArray(it->second.vao);
      if (item.spans.empty()) {
        glDrawElements(GL_TRIANGLES, it->second.indexCount, GL_UNSIGNED_INT, nullptr);
        stats.drawCalls += 1;
        stats.triangles += static_cast<std::uint64_t>(it->second.indexCount / 3) -
                           (f.showModels ? it->second.fallbackTriangles : it->second.modelTriangles);
        continue;
      }
      for (const IndexSpan& span : item.spans) {
        if (span.indexCount == 0 ||
            std::uint64_t{span.firstIndex} + span.indexCount > static_cast<std::uint64_t>(it->second.indexCount))
          continue;
        glDrawElements(
            GL_TRIANGLES, static_cast<GLsizei>(span.indexCount), GL_UNSIGNED_INT,
            reinterpret_cast<const void*>(static_cast<std::uintptr_t>(span.firstIndex) * sizeof(std::uint32_t)));
        stats.drawCalls += 1;
        stats.triangles += span.indexCount / 3 - (f.showModels ? span.fallbackTriangles : span.modelTriangles);
      }
    }
    glActiveTexture(GL_TEXTURE0);
  }
  glBindVertexArray(0);
  glDisable(GL_CULL_FACE);
  drawMarkers(f, stats);
  last_ = stats;
}

void GlRenderDevice::drawMarkers(const FrameUniforms& f, DeviceFrameStats& stats) {
  if (!ok() || f.markers.empty()) return;
  // Per vertex: centre (3), corner (2), colour (3), radius and ring (2).
  constexpr int kFloats = 10;
  static constexpr float kCorners[6][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, -1}, {1, 1}, {-1, 1}};
  markerVertices_.clear();
  for (const MapMarker& m : f.markers) {
    for (const auto& c : kCorners) {
      markerVertices_.insert(markerVertices_.end(), {m.position.x, m.position.y, m.position.z, c[0], c[1], m.color.x,
                                                     m.color.y, m.color.z, m.radiusPixels, m.selected ? 1.0f : 0.0f});
    }
  }
  const auto bytes = markerVertices_.size() * sizeof(float);
  glBindVertexArray(markerVao_);
  glBindBuffer(GL_ARRAY_BUFFER, markerBuffer_);
  if (bytes > markerBufferBytes_) {
    markerBufferBytes_ = std::max(bytes, markerBufferBytes_ * 2);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(markerBufferBytes_), nullptr, GL_DYNAMIC_DRAW);
  }
  glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(bytes), markerVertices_.data());
  constexpr auto stride = static_cast<GLsizei>(kFloats * sizeof(float));
  const int sizes[4] = {3, 2, 3, 2};
  std::size_t offset = 0;
  for (unsigned a = 0; a < 4; ++a) {
    glEnableVertexAttribArray(a);
    glVertexAttribPointer(a, sizes[a], GL_FLOAT, GL_FALSE, stride, byteOffset(offset * sizeof(float)));
    offset += static_cast<std::size_t>(sizes[a]);
  }
  glUseProgram(markerProgram_);
  glUniformMatrix4fv(markerViewProjection_, 1, GL_FALSE, &f.viewProjection[0][0]);
  glUniform2f(markerViewport_, static_cast<float>(f.viewportWidth), static_cast<float>(f.viewportHeight));
  glDisable(GL_DEPTH_TEST);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(f.markers.size() * 6));
  glEnable(GL_DEPTH_TEST);
  glBindVertexArray(0);
  pendingUpload_ += bytes;
  stats.drawCalls += 1;
  stats.triangles += 2 * f.markers.size();
}

std::size_t GlRenderDevice::gpuBytes() const {
  return meshBytes_ + (buildings_.shadow.size() + floors_.shadow.size()) * sizeof(float) + series_.shadow.size();
}

}  // namespace qv
