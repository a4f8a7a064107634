// Checks shared by the ground tile fuzz targets: the contract of a decoded tile (GroundTile.h),
// tested independently of the decoder.
#pragma once

#include <cmath>
#include <cstdint>

#include "FuzzSupport.h"
#include "qv/format/GroundTile.h"

namespace qv::fuzz {

/// The contract of a decoded tile (GroundTile.h), checked independently of the decoder.
inline void checkGroundTileConsistent(const GroundTile& t) {
  check(t.extent >= 1.0e-6f && t.extent <= 1.0e8f, "extent out of range");
  check(std::abs(t.originX) <= 1.0e7 && std::abs(t.originY) <= 1.0e7, "origin out of range");
  for (const glm::vec2& v : t.vertices) {
    check(v.x >= 0.0f && v.y >= 0.0f && v.x <= t.extent * 1.0001f && v.y <= t.extent * 1.0001f,
          "a vertex outside the cell");
  }
  check(t.triangles.size() % 3 == 0, "triangles not in triples");
  for (std::uint32_t i : t.triangles) check(i < t.vertices.size(), "an index out of range");
  std::uint64_t cursor = 0;
  for (std::size_t k = 0; k < t.runs.size(); ++k) {
    check(t.runs[k].groundClass < GroundClass::Count, "a run of an unknown class");
    check(k == 0 || t.runs[k - 1].groundClass < t.runs[k].groundClass, "runs not in increasing class order");
    check(t.runs[k].firstTriangle == cursor, "runs not contiguous");
    cursor += t.runs[k].triangleCount;
  }
  check(cursor == t.triangles.size() / 3, "runs do not cover the triangles");
  for (const GroundLabel& l : t.labels) {
    check(l.kind < GroundLabelKind::Count, "a label of an unknown kind");
    check(!l.text.empty() && l.text.size() <= 255, "a label text of a bad length");
    for (char c : l.text) check(static_cast<unsigned char>(c) >= 0x20 && c != 0x7F, "a control character in a label");
    check(l.angleRad > -1.5707964f && l.angleRad <= 1.5707964f, "a label angle out of range");
    check(l.lengthM >= 0.0f && std::isfinite(l.lengthM), "a label length out of range");
  }
}

}  // namespace qv::fuzz
