#include <catch2/catch.hpp>

#include <cmath>

#include "qv/seismic/BuildingModel.h"

using namespace qv;
using namespace qv::seismic;

namespace {

BuildingAttributes attributes(StructuralType type, CodeEra era, int storeys, float height, float area = 400.0f) {
  BuildingAttributes a;
  a.id = "w1";
  a.structuralType = type;
  a.codeEra = era;
  a.storeys = static_cast<std::uint16_t>(storeys);
  a.heightM = height;
  a.footprintAreaM2 = area;
  return a;
}

}  // namespace

TEST_CASE("The fundamental period matches the ASCE 7-16 formula within 1 %", "[seismic][model]") {
  struct Case {
    StructuralType type;
    int storeys;
    float height;
    double ct, x;
  };
  const Case cases[] = {
      {StructuralType::S1M, 5, 18.0f, 0.0724, 0.8},    {StructuralType::C1H, 20, 66.0f, 0.0466, 0.9},
      {StructuralType::W1, 2, 6.0f, 0.0488, 0.75},     {StructuralType::C2L, 1, 3.5f, 0.0488, 0.75},
      {StructuralType::S2H, 60, 220.0f, 0.0488, 0.75}, {StructuralType::C1H, 160, 600.0f, 0.0466, 0.9},
      {StructuralType::URMM, 4, 13.0f, 0.0488, 0.75},
  };
  for (const Case& c : cases) {
    CAPTURE(structuralTypeCode(c.type), c.storeys);
    const auto model = buildingModelFromAttributes(attributes(c.type, CodeEra::HighCode, c.storeys, c.height));
    REQUIRE(model.ok());
    const auto modes = computeModes(*model);
    REQUIRE(modes.ok());
    const double expected = c.ct * std::pow(static_cast<double>(c.height), c.x);
    CHECK(modes->periodsS[0] == Approx(expected).epsilon(0.01));
    CHECK(codePeriodS(c.type, c.height) == Approx(expected).epsilon(1e-12));
    // Rayleigh damping: 5 % at modes 1 and 2.
    const double w1 = modes->circularFrequencies[0];
    const double ratio1 = 0.5 * (model->damping.massCoefficient / w1 + model->damping.stiffnessCoefficient * w1);
    CHECK(ratio1 == Approx(0.05).epsilon(1e-9));
    if (c.storeys > 1) {
      const double w2 = modes->circularFrequencies[1];
      CHECK(0.5 * (model->damping.massCoefficient / w2 + model->damping.stiffnessCoefficient * w2) ==
            Approx(0.05).epsilon(1e-9));
    }
  }
}

TEST_CASE("Masses, stiffness profile and Bouc-Wen laws from the attributes", "[seismic][model]") {
  const auto model = buildingModelFromAttributes(attributes(StructuralType::C1M, CodeEra::HighCode, 5, 16.0f, 500.0f));
  REQUIRE(model.ok());
  REQUIRE(model->storeys() == 5);
  CHECK(model->floorMassKg[0] == Approx(500.0 * 1000.0));
  CHECK(model->storeyHeightM[2] == Approx(3.2));
  // Linear taper to half the base stiffness at the top storey.
  CHECK(model->storeyStiffnessNPerM[4] / model->storeyStiffnessNPerM[0] == Approx(0.5));
  CHECK(model->storeyStiffnessNPerM[2] / model->storeyStiffnessNPerM[0] == Approx(0.75));
  // Hazus C1M high code: Dy 1.15 in, Ay 0.208 g, Du 18.44 in, Au 0.624 g, h 50 ft, α2 0.75.
  const HazusCapacity c = hazusCapacity(StructuralType::C1M, CodeEra::HighCode);
  CHECK(c.yieldDriftRatio() == Approx(1.15 / (0.75 * 600.0)));
  CHECK(c.postYieldStiffnessRatio() == Approx(((0.624 - 0.208) / (18.44 - 1.15)) / (0.208 / 1.15)));
  REQUIRE(model->hysteresis.size() == 5);
  CHECK(model->hysteresis[0].yieldDisplacementM == Approx(c.yieldDriftRatio() * 3.2));
  CHECK(model->hysteresis[0].alpha == Approx(c.postYieldStiffnessRatio()));
  CHECK(model->hysteresis[0].exponent == 1.0);
  CHECK(model->damageDriftThresholds[0] == 0.0033);
  // Steel: n = 2; wood 300 kg/m², steel 700 kg/m².
  const auto steel = buildingModelFromAttributes(attributes(StructuralType::S1L, CodeEra::LowCode, 2, 7.0f));
  REQUIRE(steel.ok());
  CHECK(steel->hysteresis[0].exponent == 2.0);
  CHECK(unitFloorMassKgPerM2(StructuralType::S1L) == 700.0);
  CHECK(unitFloorMassKgPerM2(StructuralType::W1) == 300.0);
  // Hazus elastic periods from the capacity curves (cross-check of the transcription): W1 0.35 s,
  // S1L 0.50 s, C1L 0.40 s, S1H 2.21 s.
  auto elasticPeriod = [](const HazusCapacity& h) {
    return 6.283185307179586 * std::sqrt(h.yieldDisplacementIn * 0.0254 / (h.yieldAccelerationG * 9.80665));
  };
  CHECK(elasticPeriod(hazusCapacity(StructuralType::W1, CodeEra::HighCode)) == Approx(0.35).epsilon(0.02));
  CHECK(elasticPeriod(hazusCapacity(StructuralType::S1L, CodeEra::ModerateCode)) == Approx(0.50).epsilon(0.02));
  CHECK(elasticPeriod(hazusCapacity(StructuralType::C1L, CodeEra::LowCode)) == Approx(0.40).epsilon(0.02));
  CHECK(elasticPeriod(hazusCapacity(StructuralType::S1H, CodeEra::HighCode)) == Approx(2.21).epsilon(0.02));
}

TEST_CASE("Building models: defaults and absurd inputs", "[seismic][model]") {
  // No height: 3 m storeys; unknown type and era: C1 of the height class, moderate code.
  auto a = attributes(StructuralType::Unknown, CodeEra::Unknown, 10, 0.0f);
  const auto m = buildingModelFromAttributes(a);
  REQUIRE(m.ok());
  CHECK(m->structuralType == StructuralType::C1H);
  CHECK(m->codeEra == CodeEra::ModerateCode);
  CHECK(m->storeyHeightM[0] == Approx(3.0));
  // Linear option.
  BuildingModelOptions linear;
  linear.nonlinear = false;
  CHECK(buildingModelFromAttributes(a, linear)->linear());

  struct Bad {
    int storeys;
    float height;
    float area;
    const char* message;
  };
  const Bad bad[] = {
      {0, 10.0f, 100.0f, "building w1: 0 storeys (1 to 200 are modelled)"},
      {250, 800.0f, 100.0f, "building w1: 250 storeys (1 to 200 are modelled)"},
      {3, 9.0f, 0.0f, "building w1: footprint area 0 m2 (must be in (0, 1e6])"},
      {3, 9.0f, -5.0f, "building w1: footprint area -5 m2 (must be in (0, 1e6])"},
      {2, 400.0f, 100.0f, "building w1: storey height 200 m (400 m over 2 storeys; 1 to 60 m per storey are modelled)"},
  };
  for (const Bad& b : bad) {
    const auto r =
        buildingModelFromAttributes(attributes(StructuralType::W1, CodeEra::HighCode, b.storeys, b.height, b.area));
    REQUIRE_FALSE(r.ok());
    CHECK(r.error() == b.message);
  }
  auto nan = attributes(StructuralType::W1, CodeEra::HighCode, 2, std::nanf(""));
  CHECK_FALSE(buildingModelFromAttributes(nan).ok());

  // Many at once: failures stay in place with their messages.
  const std::vector<BuildingAttributes> many = {attributes(StructuralType::W1, CodeEra::HighCode, 2, 6.0f),
                                                attributes(StructuralType::W1, CodeEra::HighCode, 0, 6.0f),
                                                attributes(StructuralType::C2M, CodeEra::LowCode, 5, 16.0f)};
  const auto models = buildingModelsFromAttributes(many);
  REQUIRE(models.size() == 3);
  CHECK(models[0].ok());
  CHECK(models[1].error() == "building w1: 0 storeys (1 to 200 are modelled)");
  CHECK(models[2]->storeys() == 5);
}
