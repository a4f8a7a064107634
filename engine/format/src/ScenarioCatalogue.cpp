#include "qv/format/ScenarioCatalogue.h"

#include <simdjson.h>

#include <cmath>
#include <set>

#include "qv/core/JsonWriter.h"
#include "qv/core/NumberFormat.h"
#include "qv/core/Text.h"

namespace qv {
namespace {

using simdjson::dom::element;
using simdjson::dom::object;

/// Text from the file quoted in a message: on one line, at most 60 bytes (a hostile name may be
/// megabytes of anything).
std::string shownQuoted(std::string_view text) {
  constexpr std::size_t kShown = 60;
  const bool cut = text.size() > kShown;
  return "\"" + displaySafe(text.substr(0, kShown)) + (cut ? "..." : "") + "\"";
}

/// Messages about single bad entries before the rest are counted in one.
constexpr std::size_t kMaxEntryWarnings = 10;

bool isNameCharacter(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '-' || c == '_';
}

}  // namespace

std::string scenarioManifestProblem(std::string_view fileName) {
  if (fileName.empty()) return "is empty";
  if (fileName.size() > kMaxScenarioManifestBytes) {
    return "is longer than " + std::to_string(kMaxScenarioManifestBytes) + " bytes";
  }
  if (fileName.find_first_of("/\\") != std::string_view::npos || fileName.find("..") != std::string_view::npos) {
    return "is a path; a scenario's manifest must be a file name beside scenarios.json";
  }
  for (const char c : fileName) {
    if (!isNameCharacter(c)) {
      return "holds characters other than letters, digits, '.', '-' and '_' (a file name beside scenarios.json, "
             "never an address)";
    }
  }
  if (fileName.front() == '.') return "starts with '.'";
  constexpr std::string_view kJson = ".json";
  if (fileName.size() <= kJson.size() || fileName.substr(fileName.size() - kJson.size()) != kJson) {
    return "does not end in \".json\"";
  }
  return {};
}

std::string_view urlFileName(std::string_view url) {
  url = url.substr(0, url.find_first_of("?#"));
  const std::size_t slash = url.rfind('/');
  return slash == std::string_view::npos ? url : url.substr(slash + 1);
}

Result<ScenarioCatalogue> parseScenarioCatalogue(std::string_view json, std::string_view name) {
  const std::string prefix = std::string(name) + ": ";
  if (json.size() > kMaxScenarioCatalogueBytes) {
    return Error{prefix + "larger than " + std::to_string(kMaxScenarioCatalogueBytes >> 10) +
                 " KiB; a scenario catalogue is a short list"};
  }
  simdjson::dom::parser parser;
  element doc;
  const simdjson::padded_string padded(json.data(), json.size());
  if (const auto err = parser.parse(padded).get(doc); err != simdjson::SUCCESS) {
    return Error{prefix + "not valid JSON (" + simdjson::error_message(err) + ")"};
  }
  object root;
  if (doc.get(root) != simdjson::SUCCESS) return Error{prefix + "the scenario catalogue must be a JSON object"};
  std::string_view format;
  if (root["format"].get(format) != simdjson::SUCCESS || format != kScenarioCatalogueFormat) {
    return Error{prefix + "not a QuakeView scenario catalogue (\"format\" must be \"" +
                 std::string(kScenarioCatalogueFormat) + "\")"};
  }
  double version = 0.0;
  if (root["version"].get_double().get(version) != simdjson::SUCCESS) {
    return Error{prefix + "\"version\" missing or not a number"};
  }
  if (version != kScenarioCatalogueVersion) {
    // Printed as written: a hostile version (1e300) must not reach an integer conversion.
    return Error{prefix + "unsupported scenario catalogue version " + formatDouble(version, 10) +
                 " (this build reads version " + std::to_string(kScenarioCatalogueVersion) + ")"};
  }
  simdjson::dom::array list;
  if (root["scenarios"].get(list) != simdjson::SUCCESS) return Error{prefix + "\"scenarios\" missing or not a list"};

  ScenarioCatalogue out;
  std::set<std::uint32_t> indices;
  std::set<std::string, std::less<>> manifests;
  std::size_t position = 0;
  std::size_t beyondLimit = 0;
  std::size_t leftOut = 0;  // bad entries
  for (element e : list) {
    ++position;
    if (out.scenarios.size() >= kMaxScenarios) {
      ++beyondLimit;
      continue;
    }
    const std::string where = prefix + "entry " + std::to_string(position) + " of \"scenarios\"";
    auto leaveOut = [&](const std::string& why) {
      if (++leftOut <= kMaxEntryWarnings) out.warnings.push_back(where + " " + why + "; it is left out");
    };
    object o;
    if (e.get(o) != simdjson::SUCCESS) {
      leaveOut("is not an object");
      continue;
    }
    double index = 0.0;
    if (o["index"].get_double().get(index) != simdjson::SUCCESS) {
      leaveOut("has no number \"index\"");
      continue;
    }
    if (!(index >= 1.0 && index <= kMaxScenarioIndex) || std::floor(index) != index) {
      leaveOut("has \"index\" " + formatDouble(index, 10) + ", not a whole number from 1 to " +
               std::to_string(kMaxScenarioIndex));
      continue;
    }
    ScenarioEntry s;
    s.index = static_cast<std::uint32_t>(index);
    std::string_view text;
    if (o["name"].get(text) != simdjson::SUCCESS) {
      leaveOut("(scenario " + std::to_string(s.index) + ") has no string \"name\"");
      continue;
    }
    if (text.empty() || text.size() > kMaxScenarioNameBytes || needsDisplayCleaning(text)) {
      leaveOut("(scenario " + std::to_string(s.index) + ") has the name " + shownQuoted(text) + ", which " +
               (text.empty() ? std::string("is empty")
                : text.size() > kMaxScenarioNameBytes
                    ? "is longer than " + std::to_string(kMaxScenarioNameBytes) + " bytes"
                    : std::string("holds control characters, line breaks or bidirectional controls")));
      continue;
    }
    s.name = std::string(text);
    if (o["manifest"].get(text) != simdjson::SUCCESS) {
      leaveOut("(scenario " + std::to_string(s.index) + ") has no string \"manifest\"");
      continue;
    }
    if (const std::string problem = scenarioManifestProblem(text); !problem.empty()) {
      leaveOut("(scenario " + std::to_string(s.index) + ") has the manifest " + shownQuoted(text) + ", which " +
               problem);
      continue;
    }
    s.manifest = std::string(text);
    if (indices.count(s.index) != 0) {
      leaveOut("repeats scenario index " + std::to_string(s.index));
      continue;
    }
    if (manifests.count(s.manifest) != 0) {
      leaveOut("(scenario " + std::to_string(s.index) + ") repeats the manifest " + shownQuoted(s.manifest));
      continue;
    }
    indices.insert(s.index);
    manifests.insert(s.manifest);
    out.scenarios.push_back(std::move(s));
  }
  if (leftOut > kMaxEntryWarnings) {
    out.warnings.push_back(prefix + std::to_string(leftOut - kMaxEntryWarnings) + " more bad entries are left out");
  }
  if (beyondLimit > 0) {
    out.warnings.push_back(prefix + "lists " + std::to_string(position) + " scenarios; the first " +
                           std::to_string(kMaxScenarios) + " are read, the other " + std::to_string(beyondLimit) +
                           " left out");
  }
  return out;
}

std::string scenarioCatalogueToJson(const ScenarioCatalogue& catalogue) {
  JsonWriter w;
  w.beginObject();
  w.field("format", kScenarioCatalogueFormat).field("version", kScenarioCatalogueVersion);
  w.key("scenarios").beginArray();
  for (const ScenarioEntry& s : catalogue.scenarios) {
    w.breakLine().beginObject();
    w.field("index", s.index).field("name", s.name).field("manifest", s.manifest);
    w.endObject();
  }
  w.endArray().endObject();
  std::string out = w.take();
  out += '\n';
  return out;
}

}  // namespace qv
