// The scenario catalogue (scenarios.json): the earthquakes one city folder holds results for. Each
// scenario is a complete manifest beside the catalogue (scenario-I.json, read by parseTileset like
// tileset.json), whose `response` is that scenario's and whose files are relative to the city
// folder; tileset.json is the city's default view and may or may not be listed. A city without
// the file has no catalogue. Specification: docs/formats.md, "Scenario catalogue".
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "qv/core/Result.h"

namespace qv {

inline constexpr int kScenarioCatalogueVersion = 1;
inline constexpr std::string_view kScenarioCatalogueFormat = "quakeview-scenarios";
/// The file's name beside the city's manifests.
inline constexpr std::string_view kScenarioCatalogueFile = "scenarios.json";
/// Limits a reader applies: larger files are refused whole, entries beyond kMaxScenarios are left
/// out (with a warning), and a longer name or manifest leaves its entry out.
inline constexpr std::size_t kMaxScenarioCatalogueBytes = 1u << 20;
inline constexpr std::size_t kMaxScenarios = 1000;
inline constexpr std::size_t kMaxScenarioNameBytes = 200;
inline constexpr std::size_t kMaxScenarioManifestBytes = 128;
inline constexpr std::uint32_t kMaxScenarioIndex = 1000000;

struct ScenarioEntry {
  std::uint32_t index = 0;  ///< 1 .. kMaxScenarioIndex, unique in the catalogue
  std::string name;         ///< shown as written: one line, no control or bidirectional characters
  std::string manifest;     ///< a file name beside scenarios.json (scenarioManifestProblem is empty)
  friend bool operator==(const ScenarioEntry&, const ScenarioEntry&) = default;
};

struct ScenarioCatalogue {
  std::vector<ScenarioEntry> scenarios;  ///< in the file's order
  /// Entries left out, one message each naming the entry and what is wrong with it (the rest of the
  /// catalogue is good): the first ten bad entries each, then one message counting the others, and
  /// one for entries beyond kMaxScenarios.
  std::vector<std::string> warnings;
};

/// Why `fileName` cannot be a scenario's manifest, or empty when it can: a plain file name ending
/// in ".json", at most kMaxScenarioManifestBytes, of ASCII letters, digits, '.', '-' and '_', not
/// starting with '.' and without "..". Never a path ('/', '\\'), a URL (':'), an escape ('%') or
/// a query ('?', '#'): a catalogue must not point the viewer outside its city folder.
std::string scenarioManifestProblem(std::string_view fileName);

/// Parses a catalogue; `name` prefixes messages. Refused whole (an Error): not JSON, not an object,
/// another format or version, "scenarios" missing or not a list, more than
/// kMaxScenarioCatalogueBytes. An entry that is not an object, or whose index, name or manifest is
/// missing or bad (scenarioManifestProblem, control characters, too long), or that repeats an
/// index or a manifest, is left out with a warning; unknown keys are ignored.
Result<ScenarioCatalogue> parseScenarioCatalogue(std::string_view json, std::string_view name);

/// Serializes a catalogue (its warnings are not written), one scenario a line.
std::string scenarioCatalogueToJson(const ScenarioCatalogue& catalogue);

/// The last segment of a URL's path (no query or fragment): "a/b/scenario-2.json?v=1" ->
/// "scenario-2.json"; how the viewer finds the open manifest among the catalogue's.
std::string_view urlFileName(std::string_view url);

}  // namespace qv
