#include "qv/prep/Lod2CityModel.h"

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>

namespace qv::prep {

MeshSource meshSourceOf(const Lod2Model& model) {
  const std::string_view source = model.source;
  if (source.rfind("cityjson", 0) == 0) return MeshSource::CityJson;
  if (source.rfind("obj", 0) == 0) return MeshSource::Obj;
  if (source.rfind("osm-parts", 0) == 0) return MeshSource::OsmParts;
  if (source.rfind("synthetic", 0) == 0) return MeshSource::Synthetic;
  return MeshSource::Other;
}

Result<Building> buildingFromModel(const Lod2Model& model) {
  const SkinnedMesh& skinned = model.skinned;
  const std::size_t vertices = skinned.mesh.positions.size();
  if (vertices == 0 || !skinned.finished || skinned.mesh.kinds.size() != skinned.mesh.triangleCount()) {
    return Error{model.id + ": the model is not finished (not re-meshed at its floors)"};
  }
  if (model.footprint.size() < 3) return Error{model.id + ": the model has no footprint"};
  if (model.attributes.storeys == 0 || model.attributes.storeys > kMaxMeshStoreys) {
    return Error{model.id + ": " + std::to_string(model.attributes.storeys) + " storeys (a tile holds 1 to " +
                 std::to_string(kMaxMeshStoreys) + ")"};
  }
  if (model.farMesh.positions.size() > 65535) {
    return Error{model.id + ": the far mesh has " + std::to_string(model.farMesh.positions.size()) +
                 " vertices (at most 65535)"};
  }

  Building b;
  b.attributes = model.attributes;
  b.attributes.lod = 2;
  BuildingPart part;
  // Counter-clockwise seen from above, as BuildingPart rings must be.
  double twiceArea = 0.0;
  for (std::size_t i = 0; i < model.footprint.size(); ++i) {
    const glm::dvec2& p = model.footprint[i];
    const glm::dvec2& q = model.footprint[(i + 1) % model.footprint.size()];
    twiceArea += p.x * q.y - q.x * p.y;
  }
  part.points = model.footprint;
  if (twiceArea < 0.0) part.points.assign(model.footprint.rbegin(), model.footprint.rend());
  part.ringEnds = {static_cast<std::uint32_t>(part.points.size())};
  part.minHeightM = model.attributes.minHeightM;
  part.heightM = model.attributes.heightM;
  b.parts.push_back(std::move(part));

  BuildingMesh mesh;
  mesh.source = meshSourceOf(model);
  mesh.verticesBefore = model.verticesBefore;
  mesh.positions = skinned.mesh.positions;
  // Triangles grouped by kind, each group in the model's order.
  mesh.triangles.reserve(skinned.mesh.triangles.size());
  for (std::size_t kind = 0; kind < kMeshSurfaceKinds; ++kind) {
    for (std::size_t t = 0; t < skinned.mesh.triangleCount(); ++t) {
      if (static_cast<std::size_t>(skinned.mesh.kinds[t]) != kind) continue;
      mesh.triangles.insert(mesh.triangles.end(), skinned.mesh.triangles.begin() + static_cast<std::ptrdiff_t>(3 * t),
                            skinned.mesh.triangles.begin() + static_cast<std::ptrdiff_t>(3 * t + 3));
      ++mesh.trianglesPerKind[kind];
    }
  }
  mesh.farPositions = model.farMesh.positions;
  mesh.farTriangles.reserve(model.farMesh.triangles.size());
  for (std::uint32_t index : model.farMesh.triangles) mesh.farTriangles.push_back(static_cast<std::uint16_t>(index));
  b.mesh = std::move(mesh);
  return b;
}

}  // namespace qv::prep
