// fuzz_scenario_catalogue: arbitrary text into parseScenarioCatalogue. Every scenario read obeys the
// catalogue's rules (index range, a plain file name beside the catalogue, a one-line name, no
// repeats, at most kMaxScenarios), warnings are bounded, and write -> parse gives the same list.
#include <cstddef>
#include <cstdint>
#include <set>
#include <string_view>

#include "FuzzSupport.h"
#include "qv/core/Text.h"
#include "qv/format/ScenarioCatalogue.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace qv;
  constexpr std::string_view kName = "https://example.org/city/scenarios.json";
  const std::string_view json(reinterpret_cast<const char*>(data), size);
  const Result<ScenarioCatalogue> catalogue = parseScenarioCatalogue(json, kName);
  fuzz::checkErrorNamesInput(catalogue, kName);
  if (!catalogue.ok()) return 0;
  fuzz::check(catalogue->scenarios.size() <= kMaxScenarios, "more scenarios than the limit");
  fuzz::check(catalogue->warnings.size() <= 12, "warnings not bounded");
  std::set<std::uint32_t> indices;
  std::set<std::string> manifests;
  for (const ScenarioEntry& s : catalogue->scenarios) {
    fuzz::check(s.index >= 1 && s.index <= kMaxScenarioIndex, "index out of range");
    fuzz::check(indices.insert(s.index).second, "a repeated index");
    fuzz::check(manifests.insert(s.manifest).second, "a repeated manifest");
    fuzz::check(scenarioManifestProblem(s.manifest).empty(), "a manifest that is not a plain file name:", s.manifest);
    fuzz::check(s.manifest.find('/') == std::string::npos && s.manifest.find("..") == std::string::npos,
                "a manifest path leaves the folder:", s.manifest);
    fuzz::check(!s.name.empty() && s.name.size() <= kMaxScenarioNameBytes && !needsDisplayCleaning(s.name),
                "a name that is not one clean line:", s.name);
  }
  for (const std::string& w : catalogue->warnings) {
    fuzz::check(w.compare(0, kName.size(), kName) == 0, "a warning that does not name the file:", w);
    fuzz::check(isValidUtf8(w) && w.find('\n') == std::string::npos, "a warning that is not one clean line:", w);
  }
  const Result<ScenarioCatalogue> again = parseScenarioCatalogue(scenarioCatalogueToJson(*catalogue), kName);
  if (!again.ok()) fuzz::contractBroken("a parsed catalogue does not parse after writing:", again.error());
  fuzz::check(again->scenarios == catalogue->scenarios, "round trip changed the scenarios");
  fuzz::check(again->warnings.empty(), "a written catalogue has bad entries");
  return 0;
}
