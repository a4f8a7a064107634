#include <catch2/catch.hpp>

#include "qv/format/BuildingAttributes.h"

using namespace qv;

TEST_CASE("Structural type codes round-trip and unknown codes stay unknown", "[format][attributes]") {
  for (int i = 0; i < static_cast<int>(StructuralType::Count); ++i) {
    const auto type = static_cast<StructuralType>(i);
    CHECK(parseStructuralType(structuralTypeCode(type)) == type);
    CHECK_FALSE(structuralTypeDescription(type).empty());
  }
  CHECK(structuralTypeCode(StructuralType::C1M) == "C1M");
  CHECK(structuralTypeDescription(StructuralType::URML) == "Unreinforced masonry bearing walls, low-rise");
  CHECK(parseStructuralType("X9") == StructuralType::Unknown);
  CHECK(structuralTypeCode(static_cast<StructuralType>(200)) == "unknown");
  CHECK(parseCodeEra(codeEraName(CodeEra::HighCode)) == CodeEra::HighCode);
  CHECK(valueSourceName(ValueSource::Tagged) == "tagged");
  CHECK(importanceName(Importance::Critical) == "critical");
}

TEST_CASE("Storey height follows from height, base and storeys", "[format][attributes]") {
  BuildingAttributes a;
  a.heightM = 443.2f;
  a.storeys = 102;
  CHECK(a.storeyHeightM() == Approx(4.345f).epsilon(1e-3));
  a.minHeightM = 20.0f;
  a.heightM = 50.0f;
  a.storeys = 10;
  CHECK(a.storeyHeightM() == Approx(3.0f));
}
