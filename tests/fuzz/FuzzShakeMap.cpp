// fuzz_shakemap: ShakeMap grid.xml text through prep::shakemap: a grid or an error naming the
// input, never a crash; a grid read is consistent (every present field holds nlon x nlat finite
// values, the lattice is increasing) and can be sampled at its centre and corners.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>

#include "FuzzSupport.h"
#include "qv/prep/ShakeMap.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  qv::prep::ShakeMapLimits limits;
  limits.maxValues = 1'000'000;  // keeps each run small; the check itself is what is fuzzed
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto grid = qv::prep::parseShakeMapGrid(text, "grid.input", limits);
  qv::fuzz::checkErrorNamesInput(grid, "grid.input");
  if (!grid.ok()) return 0;
  const std::size_t nodes = grid->lonCount * grid->latCount;
  qv::fuzz::check(grid->lonCount >= 2 && grid->latCount >= 2, "a grid below 2 x 2 nodes");
  qv::fuzz::check(grid->lonMin < grid->lonMax && grid->latMin < grid->latMax, "an empty extent");
  qv::fuzz::check(grid->pga.size() == nodes, "PGA is not nlon x nlat values");
  for (const auto* field :
       {&grid->pga, &grid->pgv, &grid->mmi, &grid->psa03, &grid->psa10, &grid->psa30, &grid->vs30}) {
    qv::fuzz::check(field->empty() || field->size() == nodes, "a field is not nlon x nlat values");
    for (const float v : *field) qv::fuzz::check(std::isfinite(v), "a non-finite value was kept");
  }
  for (const auto& [lon, lat] : {std::pair{0.5 * (grid->lonMin + grid->lonMax), 0.5 * (grid->latMin + grid->latMax)},
                                 std::pair{grid->lonMin, grid->latMin}, std::pair{grid->lonMax, grid->latMax}}) {
    const auto s = qv::prep::sampleShakeMap(*grid, lon, lat);
    qv::fuzz::check(s.has_value(), "no sample inside the grid");
    qv::fuzz::check(std::isfinite(s->pgaG), "a non-finite PGA sample");
  }
  qv::fuzz::check(!qv::prep::sampleShakeMap(*grid, grid->lonMax + 1.0, grid->latMin), "a sample outside the grid");
  return 0;
}
