// fuzz_city_tile_roundtrip: builds a valid city tile from the fuzzer's bytes, encodes it and
// decodes it again. The decoder must accept what the encoder wrote and give back the same tile
// (vertices within one quantization step).
#include <fuzzer/FuzzedDataProvider.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

#include "CityTileChecks.h"
#include "FuzzSupport.h"

namespace {

using namespace qv;

std::string text(FuzzedDataProvider& in, std::size_t maxLength) {
  return in.ConsumeRandomLengthString(maxLength);
}

CityTile makeTile(FuzzedDataProvider& in) {
  CityTile t;
  t.coarse = in.ConsumeBool();
  t.originX = in.ConsumeFloatingPointInRange(-1.0e7, 1.0e7);
  t.originY = in.ConsumeFloatingPointInRange(-1.0e7, 1.0e7);
  t.extent = in.ConsumeFloatingPointInRange(0.001f, 1.0e5f);
  const int buildings = in.ConsumeIntegralInRange(0, 8);
  for (int b = 0; b < buildings; ++b) {
    TileBuilding building;
    building.firstPart = static_cast<std::uint32_t>(t.parts.size());
    building.partCount = in.ConsumeIntegralInRange<std::uint16_t>(1, 3);
    for (std::uint16_t k = 0; k < building.partCount; ++k) {
      TilePart p;
      p.firstRing = static_cast<std::uint32_t>(t.ringVertexCounts.size());
      p.firstVertex = static_cast<std::uint32_t>(t.vertices.size());
      p.firstTriangle = static_cast<std::uint32_t>(t.roofTriangles.size() / 3);
      p.ringCount = in.ConsumeIntegralInRange<std::uint16_t>(1, 3);
      for (std::uint16_t r = 0; r < p.ringCount; ++r) {
        const auto n = in.ConsumeIntegralInRange<std::uint16_t>(3, 40);
        t.ringVertexCounts.push_back(n);
        for (std::uint16_t v = 0; v < n; ++v) {
          t.vertices.push_back(
              {in.ConsumeFloatingPointInRange(0.0f, t.extent), in.ConsumeFloatingPointInRange(0.0f, t.extent)});
        }
        p.vertexCount += n;
      }
      p.triangleCount = in.ConsumeIntegralInRange<std::uint32_t>(0, 30);
      for (std::uint32_t i = 0; i < p.triangleCount * 3; ++i) {
        t.roofTriangles.push_back(
            in.ConsumeIntegralInRange<std::uint16_t>(0, static_cast<std::uint16_t>(p.vertexCount - 1)));
      }
      p.minHeightM = in.ConsumeFloatingPointInRange(-1000.0f, 5000.0f);
      p.heightM = in.ConsumeFloatingPointInRange(p.minHeightM, 10000.0f);
      p.roofHeightM = in.ConsumeFloatingPointInRange(0.0f, 100.0f);
      p.roofShape = in.ConsumeBool() ? RoofShape::Other : static_cast<RoofShape>(in.ConsumeIntegralInRange(0, 11));
      t.parts.push_back(p);
    }
    BuildingAttributes& a = building.attributes;
    a.id = "b" + text(in, 200);
    a.name = text(in, 300);
    a.use = text(in, 40);
    a.address = text(in, 300);
    a.material = text(in, 40);
    a.structure = text(in, 40);
    a.amenity = text(in, 40);
    a.minHeightM = in.ConsumeFloatingPointInRange(-100.0f, 1000.0f);
    a.heightM = in.ConsumeFloatingPointInRange(a.minHeightM, 2000.0f);
    a.storeys = in.ConsumeIntegralInRange<std::uint16_t>(1, 500);
    a.heightSource = in.ConsumeBool() ? ValueSource::Tagged : ValueSource::Inferred;
    a.storeysSource = in.ConsumeBool() ? ValueSource::Tagged : ValueSource::Inferred;
    a.startYear = in.ConsumeIntegral<std::int16_t>();
    a.structuralType = static_cast<StructuralType>(
        in.ConsumeIntegralInRange<std::uint8_t>(0, static_cast<std::uint8_t>(StructuralType::Count) - 1));
    a.codeEra =
        static_cast<CodeEra>(in.ConsumeIntegralInRange<std::uint8_t>(0, static_cast<std::uint8_t>(CodeEra::Count) - 1));
    a.importance = in.ConsumeBool() ? Importance::Critical : Importance::General;
    a.importanceReasons = in.ConsumeIntegral<std::uint8_t>();
    a.lod = in.ConsumeIntegral<std::uint8_t>();
    a.footprintAreaM2 = in.ConsumeFloatingPointInRange(0.0f, 1.0e6f);
    a.centroidX = static_cast<float>(in.ConsumeFloatingPointInRange(-1.0e5, 1.0e5));
    a.centroidY = static_cast<float>(in.ConsumeFloatingPointInRange(-1.0e5, 1.0e5));
    t.buildings.push_back(building);
  }
  // LOD2 models (MESH) for some buildings whose storeys fit a skeleton.
  for (std::uint32_t b = 0; b < t.buildings.size(); ++b) {
    const std::uint16_t storeys = t.buildings[b].attributes.storeys;
    if (storeys > kMaxMeshStoreys || !in.ConsumeBool()) continue;
    TileMesh m;
    m.building = b;
    m.source = static_cast<MeshSource>(in.ConsumeIntegralInRange(0, 2));
    m.storeys = storeys;
    m.verticesBefore = in.ConsumeIntegral<std::uint32_t>();
    m.topM = in.ConsumeFloatingPointInRange(0.01f, 10000.0f);  // the decoder's range
    const auto vertices = in.ConsumeIntegralInRange<std::uint32_t>(1, in.ConsumeBool() ? 70000 : 60);
    for (std::uint32_t i = 0; i < vertices; ++i) {
      m.positions.push_back({in.ConsumeFloatingPointInRange(0.0f, t.extent),
                             in.ConsumeFloatingPointInRange(0.0f, t.extent),
                             in.ConsumeFloatingPointInRange(0.0f, m.topM)});
    }
    for (std::uint32_t& n : m.trianglesPerKind) {
      n = in.ConsumeIntegralInRange<std::uint32_t>(0, 20);
      for (std::uint32_t i = 0; i < n * 3; ++i)
        m.triangles.push_back(in.ConsumeIntegralInRange<std::uint32_t>(0, vertices - 1));
    }
    const auto farVertices = in.ConsumeIntegralInRange<std::uint16_t>(1, 40);
    for (std::uint16_t i = 0; i < farVertices; ++i) {
      m.farPositions.push_back({in.ConsumeFloatingPointInRange(0.0f, t.extent),
                                in.ConsumeFloatingPointInRange(0.0f, t.extent),
                                in.ConsumeFloatingPointInRange(0.0f, m.topM)});
    }
    const int farTriangles = in.ConsumeIntegralInRange(0, 20);
    for (int i = 0; i < farTriangles * 3; ++i) {
      m.farTriangles.push_back(
          in.ConsumeIntegralInRange<std::uint16_t>(0, static_cast<std::uint16_t>(farVertices - 1)));
    }
    t.meshes.push_back(std::move(m));
  }
  return t;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  const CityTile tile = makeTile(in);
  const Result<CityTile> decoded = decodeCityTile(encodeCityTile(tile), "roundtrip.qvt");
  if (!decoded.ok()) fuzz::contractBroken("the decoder rejects what the encoder wrote:", decoded.error());
  fuzz::checkTileConsistent(*decoded);
  fuzz::checkSameTile(tile, *decoded, tile.extent / 65535.0f);
  return 0;
}
