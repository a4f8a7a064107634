// What the viewer relies on in a decoded city tile, and tile equality for the round trips.
#pragma once

#include <cmath>
#include <cstddef>

#include "FuzzSupport.h"
#include "qv/format/CityTile.h"

namespace qv::fuzz {

/// Every range a decoded tile holds lies inside its arrays; every index is in range.
inline void checkTileConsistent(const CityTile& t) {
  std::size_t vertexTotal = 0;
  for (std::uint16_t n : t.ringVertexCounts) vertexTotal += n;
  check(vertexTotal == t.vertices.size(), "ring vertex counts do not add up to the vertices");
  check(t.roofTriangles.size() % 3 == 0, "roof triangles are not triples");
  for (const TilePart& p : t.parts) {
    check(std::size_t{p.firstRing} + p.ringCount <= t.ringVertexCounts.size(), "part rings out of range");
    check(std::size_t{p.firstVertex} + p.vertexCount <= t.vertices.size(), "part vertices out of range");
    check(std::size_t{p.firstTriangle} + p.triangleCount <= t.roofTriangles.size() / 3, "part triangles out of range");
    for (std::size_t i = std::size_t{p.firstTriangle} * 3; i < (std::size_t{p.firstTriangle} + p.triangleCount) * 3;
         ++i) {
      check(t.roofTriangles[i] < p.vertexCount, "triangle index beyond its part");
    }
    check(std::isfinite(p.heightM) && std::isfinite(p.minHeightM), "non-finite part height");
  }
  for (const TileBuilding& b : t.buildings) {
    check(b.partCount > 0 && std::size_t{b.firstPart} + b.partCount <= t.parts.size(), "building parts out of range");
    check(!b.attributes.id.empty(), "building without id");
    check(std::isfinite(b.attributes.heightM) && b.attributes.storeys > 0, "invalid building values");
  }
  for (const auto& v : t.vertices) {
    check(std::isfinite(v.x) && std::isfinite(v.y), "non-finite vertex");
  }
  for (std::size_t k = 0; k < t.meshes.size(); ++k) {
    const TileMesh& m = t.meshes[k];
    check(m.building < t.buildings.size(), "mesh building out of range");
    check(k == 0 || m.building > t.meshes[k - 1].building, "mesh buildings not increasing");
    check(m.storeys == t.buildings[m.building].attributes.storeys, "mesh storeys differ from the building's");
    std::size_t triangles = 0;
    for (std::uint32_t n : m.trianglesPerKind) triangles += n;
    check(triangles * 3 == m.triangles.size(), "mesh triangles per kind do not add up");
    for (std::uint32_t i : m.triangles) check(i < m.positions.size(), "mesh index out of range");
    check(m.farTriangles.size() % 3 == 0, "far triangles are not triples");
    for (std::uint16_t i : m.farTriangles) check(i < m.farPositions.size(), "far index out of range");
    for (const auto& p : m.positions) {
      check(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z), "non-finite mesh vertex");
    }
  }
}

inline bool sameAttributes(const BuildingAttributes& a, const BuildingAttributes& b) {
  return a.id == b.id && a.name == b.name && a.use == b.use && a.address == b.address && a.material == b.material &&
         a.structure == b.structure && a.amenity == b.amenity && a.heightM == b.heightM &&
         a.minHeightM == b.minHeightM && a.storeys == b.storeys && a.heightSource == b.heightSource &&
         a.storeysSource == b.storeysSource && a.startYear == b.startYear && a.structuralType == b.structuralType &&
         a.codeEra == b.codeEra && a.importance == b.importance && a.importanceReasons == b.importanceReasons &&
         a.lod == b.lod && a.footprintAreaM2 == b.footprintAreaM2 &&
         static_cast<float>(a.centroidX) == static_cast<float>(b.centroidX) &&
         static_cast<float>(a.centroidY) == static_cast<float>(b.centroidY);
}

/// Equality of everything a tile stores; vertices within `vertexTolerance` metres (the
/// quantization step when one side was not decoded).
inline void checkSameTile(const CityTile& a, const CityTile& b, float vertexTolerance) {
  check(a.coarse == b.coarse && a.originX == b.originX && a.originY == b.originY && a.extent == b.extent,
        "round trip changed the header");
  check(a.ringVertexCounts == b.ringVertexCounts, "round trip changed the rings");
  check(a.roofTriangles == b.roofTriangles, "round trip changed the roof triangles");
  check(a.vertices.size() == b.vertices.size(), "round trip changed the vertex count");
  for (std::size_t i = 0; i < a.vertices.size(); ++i) {
    check(std::fabs(a.vertices[i].x - b.vertices[i].x) <= vertexTolerance &&
              std::fabs(a.vertices[i].y - b.vertices[i].y) <= vertexTolerance,
          "round trip moved a vertex");
  }
  check(a.parts.size() == b.parts.size(), "round trip changed the part count");
  for (std::size_t i = 0; i < a.parts.size(); ++i) {
    const TilePart& p = a.parts[i];
    const TilePart& q = b.parts[i];
    check(p.firstVertex == q.firstVertex && p.vertexCount == q.vertexCount && p.firstRing == q.firstRing &&
              p.ringCount == q.ringCount && p.firstTriangle == q.firstTriangle && p.triangleCount == q.triangleCount &&
              p.minHeightM == q.minHeightM && p.heightM == q.heightM && p.roofHeightM == q.roofHeightM &&
              p.roofShape == q.roofShape,
          "round trip changed a part");
  }
  check(a.buildings.size() == b.buildings.size(), "round trip changed the building count");
  for (std::size_t i = 0; i < a.buildings.size(); ++i) {
    check(a.buildings[i].firstPart == b.buildings[i].firstPart &&
              a.buildings[i].partCount == b.buildings[i].partCount &&
              sameAttributes(a.buildings[i].attributes, b.buildings[i].attributes),
          "round trip changed a building");
  }
  check(a.meshes.size() == b.meshes.size(), "round trip changed the mesh count");
  for (std::size_t k = 0; k < a.meshes.size(); ++k) {
    const TileMesh& m = a.meshes[k];
    const TileMesh& n = b.meshes[k];
    check(m.building == n.building && m.source == n.source && m.storeys == n.storeys &&
              m.verticesBefore == n.verticesBefore && m.topM == n.topM && m.triangles == n.triangles &&
              m.trianglesPerKind == n.trianglesPerKind && m.farTriangles == n.farTriangles &&
              m.positions.size() == n.positions.size() && m.farPositions.size() == n.farPositions.size(),
          "round trip changed a mesh");
    const float zTolerance = m.topM / 65535.0f;
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
      check(std::fabs(m.positions[i].x - n.positions[i].x) <= vertexTolerance &&
                std::fabs(m.positions[i].y - n.positions[i].y) <= vertexTolerance &&
                std::fabs(m.positions[i].z - n.positions[i].z) <= zTolerance,
            "round trip moved a mesh vertex");
    }
    for (std::size_t i = 0; i < m.farPositions.size(); ++i) {
      check(std::fabs(m.farPositions[i].x - n.farPositions[i].x) <= vertexTolerance &&
                std::fabs(m.farPositions[i].y - n.farPositions[i].y) <= vertexTolerance &&
                std::fabs(m.farPositions[i].z - n.farPositions[i].z) <= zTolerance,
            "round trip moved a far vertex");
    }
  }
}

}  // namespace qv::fuzz
