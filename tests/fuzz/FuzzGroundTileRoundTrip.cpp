// fuzz_ground_tile_roundtrip: builds a valid ground tile from the fuzzer's bytes (16-bit indices,
// and now and then just over 65535 vertices for 32-bit ones), encodes it and decodes it again. The
// decoder must accept what the encoder wrote and give the same tile back (vertices and label
// positions within one quantization step), which encodes to the same bytes again.
#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "FuzzSupport.h"
#include "GroundTileChecks.h"
#include "qv/format/GroundTile.h"

namespace {

using namespace qv;

constexpr std::string_view kName = "roundtrip.qvg";

std::string labelText(FuzzedDataProvider& in) {
  // Printable ASCII and a few multi-byte characters: always a valid name.
  static constexpr const char* kPieces[] = {"Straße", "Avenue", " of the ", "東京", "Ωμέγα", "-", "'", "é", "🏙"};
  std::string text;
  const int pieces = in.ConsumeIntegralInRange(1, 12);
  for (int i = 0; i < pieces; ++i) {
    if (in.ConsumeBool()) {
      text += kPieces[in.ConsumeIntegralInRange<std::size_t>(0, std::size(kPieces) - 1)];
    } else {
      text += static_cast<char>(in.ConsumeIntegralInRange(0x20, 0x7E));
    }
  }
  return text;  // at most 12 pieces of at most 8 bytes
}

GroundTile makeTile(FuzzedDataProvider& in) {
  GroundTile t;
  t.originX = in.ConsumeFloatingPointInRange(-1.0e7, 1.0e7);
  t.originY = in.ConsumeFloatingPointInRange(-1.0e7, 1.0e7);
  t.extent = in.ConsumeFloatingPointInRange(0.001f, 1.0e6f);
  // Now and then just around 65535 vertices, where the indices become 32-bit (the rest stays fast).
  const bool many = in.ConsumeIntegralInRange(0, 15) == 15;  // an exhausted input gives 0
  const auto vertices =
      many ? in.ConsumeIntegralInRange<std::uint32_t>(65530, 65600) : in.ConsumeIntegralInRange<std::uint32_t>(0, 64);
  // The first 64 vertices from the input, the rest (only when many) on a fixed pattern: the wide
  // index path needs the count, not 65536 fuzzed positions.
  t.vertices.resize(vertices);
  for (std::uint32_t i = 0; i < vertices; ++i) {
    if (i < 64) {
      t.vertices[i] = {in.ConsumeFloatingPointInRange(0.0f, t.extent), in.ConsumeFloatingPointInRange(0.0f, t.extent)};
    } else {
      t.vertices[i] = glm::vec2(static_cast<float>(i % 256), static_cast<float>(i / 256)) * (t.extent / 256.0f);
    }
  }
  if (vertices > 0) {
    for (std::uint8_t c = 0; c < static_cast<std::uint8_t>(GroundClass::Count); ++c) {
      if (!in.ConsumeBool()) continue;
      GroundRun run{static_cast<GroundClass>(c), static_cast<std::uint32_t>(t.triangles.size() / 3),
                    in.ConsumeIntegralInRange<std::uint32_t>(0, 20)};
      for (std::uint32_t i = 0; i < run.triangleCount * 3; ++i) {
        t.triangles.push_back(in.ConsumeIntegralInRange<std::uint32_t>(0, vertices - 1));
      }
      t.runs.push_back(run);
    }
  }
  const int labels = in.ConsumeIntegralInRange(0, 8);
  for (int i = 0; i < labels; ++i) {
    GroundLabel l;
    l.kind = static_cast<GroundLabelKind>(
        in.ConsumeIntegralInRange<std::uint8_t>(0, static_cast<std::uint8_t>(GroundLabelKind::Count) - 1));
    l.rank = in.ConsumeIntegral<std::uint8_t>();
    l.position = {in.ConsumeFloatingPointInRange(0.0f, t.extent), in.ConsumeFloatingPointInRange(0.0f, t.extent)};
    l.angleRad = in.ConsumeFloatingPointInRange(-1.5707963f, 1.5707964f);
    l.lengthM = in.ConsumeFloatingPointInRange(0.0f, 1.0e5f);
    l.text = labelText(in);
    t.labels.push_back(std::move(l));
  }
  return t;
}

void roundTrip(FuzzedDataProvider& in) {
  const GroundTile tile = makeTile(in);
  const std::vector<std::uint8_t> bytes = encodeGroundTile(tile);
  const Result<GroundTile> decoded = decodeGroundTile(bytes, kName);
  if (!decoded.ok()) fuzz::contractBroken("the decoder rejects what the encoder wrote:", decoded.error());
  fuzz::checkGroundTileConsistent(*decoded);
  const float step = tile.extent / 65535.0f;
  using fuzz::check;
  check(decoded->originX == tile.originX && decoded->originY == tile.originY && decoded->extent == tile.extent,
        "round trip changed the cell");
  check(decoded->vertices.size() == tile.vertices.size(), "round trip changed the vertex count");
  for (std::size_t i = 0; i < tile.vertices.size(); ++i) {
    check(std::abs(decoded->vertices[i].x - tile.vertices[i].x) <= step &&
              std::abs(decoded->vertices[i].y - tile.vertices[i].y) <= step,
          "round trip moved a vertex by more than a quantization step");
  }
  check(decoded->triangles == tile.triangles, "round trip changed the triangles");
  check(decoded->runs.size() == tile.runs.size(), "round trip changed the runs");
  check(decoded->labels.size() == tile.labels.size(), "round trip changed the labels");
  for (std::size_t i = 0; i < tile.labels.size(); ++i) {
    const GroundLabel& a = tile.labels[i];
    const GroundLabel& b = decoded->labels[i];
    check(a.kind == b.kind && a.rank == b.rank && a.angleRad == b.angleRad && a.lengthM == b.lengthM &&
              a.text == b.text && std::abs(a.position.x - b.position.x) <= step &&
              std::abs(a.position.y - b.position.y) <= step,
          "round trip changed a label");
  }
  check(encodeGroundTile(*decoded) == bytes, "a decoded tile does not encode to the same bytes");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  roundTrip(in);
  return 0;
}
