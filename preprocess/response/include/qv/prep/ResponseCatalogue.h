// A scenario catalogue (`response --catalogue FILE --scenario I`, docs/cluster.md): several
// earthquakes for one city, each published as its own response beside the others, so the viewer
// can switch between them (scenarios.json).
//
// The file is JSON: {"options": {...}, "scenarios": [{"name": "...", ...}, ...]}. Each scenario's
// keys other than "name" are `response` options without their dashes ("shakemap": "grid.xml",
// "epicentre": "-74,40.7,10", "magnitude": 6.5, "synthetic": [1, 2, 3], "accurate-steps": true);
// "options" holds those every scenario shares (a scenario's own value wins). Values are text,
// numbers, true (a flag) or lists of them (an option given several values). File options
// (motion, motion-y, shakemap, districts) are relative to the catalogue's folder.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "qv/core/Result.h"
#include "qv/format/ScenarioCatalogue.h"

namespace qv::prep {

struct CatalogueScenario {
  std::string name;  ///< shown in the viewer's list; 1 to kMaxScenarioNameBytes, nothing needsDisplayCleaning
  std::vector<std::string> args;  ///< the `response` arguments it stands for, e.g. {"--shakemap", "/data/x.xml"}
};

struct Catalogue {
  std::vector<CatalogueScenario> scenarios;  ///< at least one; index I of the command line is scenarios[I - 1]
};

/// At most this many scenarios in a catalogue: as many as the viewer reads from scenarios.json.
inline constexpr std::size_t kMaxScenarios = qv::kMaxScenarios;

/// Parses a catalogue's text; `folder` is the catalogue file's folder (for relative file options).
/// Errors name `name` and the scenario.
Result<Catalogue> parseCatalogue(std::string_view json, const std::string& folder, const std::string& name);
Result<Catalogue> readCatalogue(const std::string& path);

/// The catalogue's index for the viewer, `scenarios.json` in the city folder (written and read
/// by qv/format/ScenarioCatalogue.h): per scenario its index, name and manifest
/// (`scenario-I.json`). Every scenario run writes the same file.
std::string scenarioManifestName(std::size_t index);
std::string scenariosToJson(const std::vector<std::string>& names);
/// The manifest files a city's scenarios.json lists (empty when there is none or it is not one).
std::vector<std::string> scenarioManifestsOf(const std::string& cityDir);

}  // namespace qv::prep
