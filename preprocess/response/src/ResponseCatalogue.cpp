#include "qv/prep/ResponseCatalogue.h"

#include <simdjson.h>

#include <map>
#include <set>

#include "qv/core/JsonWriter.h"
#include "qv/core/Text.h"
#include "qv/format/ScenarioCatalogue.h"
#include "qv/prep/Files.h"

namespace qv::prep {
namespace {

// Options a catalogue may not set: they say where and how the run goes, not what it computes.
const std::set<std::string, std::less<>> kNotInCatalogue = {"city",     "shard",   "merge", "catalogue",
                                                            "scenario", "threads", "help",  "list"};
const std::set<std::string, std::less<>> kFileOptions = {"motion", "motion-y", "shakemap", "districts"};

std::string resolve(const std::string& folder, const std::string& path) {
  if (path.empty() || path[0] == '/' || folder.empty()) return path;
  return folder + "/" + path;
}

// One value of an option as an argument; false when it is not text, a number or true.
bool valueText(simdjson::dom::element e, std::string& out) {
  std::string_view s;
  double d = 0;
  std::int64_t i = 0;
  if (e.get(s) == simdjson::SUCCESS) {
    out = std::string(s);
    return true;
  }
  if (e.get(i) == simdjson::SUCCESS) {
    out = std::to_string(i);
    return true;
  }
  if (e.get(d) == simdjson::SUCCESS) {
    JsonWriter w;
    w.value(d);
    out = w.str();
    return true;
  }
  return false;
}

// An object's options as (key, values); an empty list of values is a flag.
Status readOptions(simdjson::dom::object o, const std::string& where, const std::string& folder,
                   std::map<std::string, std::vector<std::string>>& out) {
  for (auto field : o) {
    const std::string key(field.key);
    if (key == "name") continue;
    if (key.empty() || key.size() > 40 || key[0] == '-' ||
        key.find_first_not_of("abcdefghijklmnopqrstuvwxyz-") != std::string::npos) {
      return Error{where + ": \"" + key.substr(0, 40) +
                   "\" is not an option name (write response options without their dashes)"};
    }
    if (kNotInCatalogue.count(key) != 0) {
      return Error{where + ": \"" + key + "\" cannot be set in a catalogue (give it on the command line)"};
    }
    std::vector<std::string> values;
    bool flag = false;
    simdjson::dom::array list;
    if (field.value.get(flag) == simdjson::SUCCESS) {
      if (!flag) continue;  // false: the flag is not given
    } else if (field.value.get(list) == simdjson::SUCCESS) {
      if (list.size() == 0 || list.size() > 1000) return Error{where + ": \"" + key + "\" needs 1 to 1000 values"};
      for (simdjson::dom::element e : list) {
        std::string v;
        if (!valueText(e, v)) return Error{where + ": \"" + key + "\" holds a value that is not text or a number"};
        values.push_back(v);
      }
    } else {
      std::string v;
      if (!valueText(field.value, v)) return Error{where + ": \"" + key + "\" is not text, a number, true or a list"};
      values.push_back(v);
    }
    for (const std::string& v : values) {
      // The values become arguments: one that reads as an option would set that option instead.
      if (v.rfind("--", 0) == 0) {
        return Error{where + ": \"" + key + "\" has the value \"" + v.substr(0, 40) +
                     "\", which reads as an option, not a value"};
      }
    }
    if (kFileOptions.count(key) != 0) {
      for (std::string& v : values) v = resolve(folder, v);
    }
    out[key] = std::move(values);
  }
  return {};
}

}  // namespace

Result<Catalogue> parseCatalogue(std::string_view json, const std::string& folder, const std::string& name) {
  simdjson::dom::parser parser;
  simdjson::dom::object root;
  if (parser.parse(json.data(), json.size()).get(root) != simdjson::SUCCESS) {
    return Error{name + ": not valid JSON (a catalogue is {\"options\": {...}, \"scenarios\": [...]})"};
  }
  std::map<std::string, std::vector<std::string>> shared;
  simdjson::dom::object options;
  if (root["options"].get(options) == simdjson::SUCCESS) {
    if (Status s = readOptions(options, name + " \"options\"", folder, shared); !s.ok()) return Error{s.error()};
  }
  simdjson::dom::array scenarios;
  if (root["scenarios"].get(scenarios) != simdjson::SUCCESS || scenarios.size() == 0) {
    return Error{name + ": \"scenarios\" must be a list of at least one scenario"};
  }
  if (scenarios.size() > kMaxScenarios) {
    return Error{name + ": " + std::to_string(scenarios.size()) + " scenarios (at most " +
                 std::to_string(kMaxScenarios) + ")"};
  }
  Catalogue out;
  std::set<std::string> names;
  for (simdjson::dom::element e : scenarios) {
    const std::string where = name + " scenario " + std::to_string(out.scenarios.size() + 1);
    simdjson::dom::object o;
    if (e.get(o) != simdjson::SUCCESS) return Error{where + ": not an object"};
    std::string_view text;
    if (o["name"].get(text) != simdjson::SUCCESS || text.empty() || text.size() > kMaxScenarioNameBytes) {
      return Error{where + ": needs a \"name\" of 1 to " + std::to_string(kMaxScenarioNameBytes) + " bytes"};
    }
    // The viewer leaves out a name it could not show as written (qv/format/ScenarioCatalogue.h).
    if (needsDisplayCleaning(text)) {
      return Error{where + ": its name holds a control character, a line break or a bidirectional control"};
    }
    CatalogueScenario s;
    s.name = std::string(text);
    if (!names.insert(s.name).second) return Error{where + ": another scenario is also named \"" + s.name + "\""};
    std::map<std::string, std::vector<std::string>> own = shared;
    std::map<std::string, std::vector<std::string>> mine;
    if (Status st = readOptions(o, where, folder, mine); !st.ok()) return Error{st.error()};
    for (auto& [key, values] : mine) own[key] = std::move(values);
    for (const auto& [key, values] : own) {
      s.args.push_back("--" + key);
      s.args.insert(s.args.end(), values.begin(), values.end());
    }
    out.scenarios.push_back(std::move(s));
  }
  return out;
}

Result<Catalogue> readCatalogue(const std::string& path) {
  auto text = readTextFile(path, 16ull << 20);
  if (!text.ok()) return Error{text.error()};
  const std::size_t slash = path.find_last_of('/');
  return parseCatalogue(*text, slash == std::string::npos ? std::string() : path.substr(0, slash), path);
}

std::string scenarioManifestName(std::size_t index) {
  return "scenario-" + std::to_string(index) + ".json";
}

std::string scenariosToJson(const std::vector<std::string>& names) {
  ScenarioCatalogue catalogue;
  for (std::size_t i = 0; i < names.size(); ++i) {
    catalogue.scenarios.push_back({static_cast<std::uint32_t>(i + 1), names[i], scenarioManifestName(i + 1)});
  }
  return scenarioCatalogueToJson(catalogue);
}

std::vector<std::string> scenarioManifestsOf(const std::string& cityDir) {
  std::vector<std::string> out;
  const std::string path = cityDir + "/" + std::string(kScenarioCatalogueFile);
  auto text = readTextFile(path, kMaxScenarioCatalogueBytes);
  if (!text.ok()) return out;
  auto catalogue = parseScenarioCatalogue(*text, path);
  if (!catalogue.ok()) return out;
  for (const ScenarioEntry& s : catalogue->scenarios) out.push_back(s.manifest);
  return out;
}

}  // namespace qv::prep
