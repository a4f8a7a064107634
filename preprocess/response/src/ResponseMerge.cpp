// The merge of a sharded response run's parts (ResponseParts.h mergeCityResponse): every part
// checked present, complete and of the same run, the leaves adopted, the city-wide totals computed
// as a one-machine run does, and the response published at once.
#include <dirent.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <set>

#include "ResponseFinish.h"
#include "ResponsePartFiles.h"
#include "qv/core/Crc32.h"
#include "qv/format/CityTile.h"
#include "qv/format/ResponseTile.h"
#include "qv/format/StoredFile.h"
#include "qv/prep/Cli.h"
#include "qv/prep/Files.h"
#include "qv/prep/ResponseCatalogue.h"
#include "qv/prep/ResponseParts.h"

namespace qv::prep {

using detail::cityManifestIdentity;
using detail::damagedPartFile;
using detail::describePart;
using detail::kPartManifest;
using detail::parsePartManifest;
using detail::PartLeafEntry;
using detail::PartManifest;
using detail::readPartFile;
using detail::resultsFromSummary;

// --- the merge ---------------------------------------------------------------------------------

namespace {
// A failed item of a parallel loop: its message kept, and the others told to stop.
struct Failure {
  std::string& message;
  std::atomic<bool>& failed;
  void operator()(std::string text) const {
    message = std::move(text);
    failed = true;
  }
};
}  // namespace

std::string stagingFolder(std::size_t scenario) {
  return scenario == 0 ? std::string(kStagingFolder)
                       : std::string(kStagingFolder) + "/scenario-" + std::to_string(scenario);
}

Result<ResponseRunReport> mergeCityResponse(const std::string& dir, std::size_t scenario, unsigned threads) {
  namespace fs = std::filesystem;
  const auto start = std::chrono::steady_clock::now();
  auto text = readTextFile(dir + "/tileset.json", 256ull << 20);
  if (!text.ok()) return Error{text.error() + " (is " + dir + " a QuakeView city directory?)"};
  auto parsed = parseTileset(*text, dir + "/tileset.json");
  if (!parsed.ok()) return Error{parsed.error()};
  const Tileset tileset = std::move(parsed).value();
  const std::string staging = dir + "/" + stagingFolder(scenario);

  // The parts there, finished (part-K-of-N with its part.json) and not (temporary folders).
  std::vector<std::string> finished, unfinished;
  {
    std::error_code ec;
    if (!fs::is_directory(staging, ec)) {
      return Error{"no parts to merge: " + staging +
                   " does not exist (run `quakeview-prep response --city DIR ... --shard K/N` for every part first)"};
    }
    for (const fs::directory_entry& e : fs::directory_iterator(staging, ec)) {
      const std::string name = e.path().filename().string();
      if (name.rfind("part-", 0) == 0 && name.find(".old-") == std::string::npos) finished.push_back(name);
      if (scenario == 0 && name.rfind("scenario-", 0) == 0) {
        return Error{staging + " holds the parts of a catalogue's scenarios (" + name +
                     "): merge them with --merge --scenario I"};
      }
      if (name.rfind(".part-", 0) == 0) unfinished.push_back(name);
    }
    if (ec) return Error{staging + ": cannot list the folder (" + ec.message() + ")"};
  }
  std::sort(finished.begin(), finished.end());
  if (finished.empty()) {
    return Error{"no finished part in " + staging +
                 (unfinished.empty() ? std::string() : " (unfinished or failed: " + unfinished.front() + ")") +
                 "; run every part with --shard K/N first"};
  }
  std::map<unsigned, std::pair<std::string, PartManifest>> parts;  // part number -> folder, manifest
  std::set<unsigned> partCounts;
  for (const std::string& name : finished) {
    const std::string path = staging + "/" + name + "/" + kPartManifest;
    auto json = readTextFile(path, 256ull << 20);
    if (!json.ok()) {
      return Error{name + " is incomplete: " + json.error() + " (re-run the part)"};
    }
    auto m = parsePartManifest(*json, path);
    if (!m.ok()) return Error{m.error()};
    if (partFolderName(m->shard) != name)
      return Error{path + ": says it is " + describePart(m->shard) + ", not " + name};
    partCounts.insert(m->shard.parts);
    parts.emplace(m->shard.part, std::make_pair(staging + "/" + name, std::move(m).value()));
  }
  if (partCounts.size() > 1) {
    std::string counts;
    for (const unsigned n : partCounts) counts += (counts.empty() ? "" : ", ") + std::to_string(n);
    return Error{staging + " holds parts of runs split into different numbers of parts (" + counts +
                 "); remove the folders of the run you do not want (e.g. " + staging + "/part-*-of-" +
                 std::to_string(*partCounts.begin()) + ") and merge again"};
  }
  const unsigned n = *partCounts.begin();
  std::vector<std::string> missing;
  std::string rerun;
  for (unsigned k = 1; k <= n; ++k) {
    if (parts.count(k) == 0) {
      rerun += (rerun.empty() ? "--shard " : ", ") + std::to_string(k) + "/" + std::to_string(n);
      const std::string tmp = "." + partFolderName({k, n}) + ".tmp-";
      const bool started =
          std::any_of(unfinished.begin(), unfinished.end(), [&](const std::string& u) { return u.rfind(tmp, 0) == 0; });
      missing.push_back(describePart({k, n}) + (started ? " (started, but failed or still running)" : ""));
    }
  }
  if (!missing.empty()) {
    std::string list;
    for (std::size_t i = 0; i < missing.size(); ++i) list += (i == 0 ? "" : ", ") + missing[i];
    return Error{"cannot merge: " + list + (missing.size() == 1 ? " is" : " are") + " missing in " + staging +
                 "; run " + (missing.size() == 1 ? "it" : "them") +
                 (scenario > 0
                      ? " (`response --catalogue FILE --scenario " + std::to_string(scenario) + "` with " + rerun + ")"
                      : " (`response` with the run's options and " + rerun + ")") +
                 " and merge again. Nothing was published; the city's response is unchanged."};
  }
  // One run: every part's identity equals part 1's, and the city is still the one they were made of.
  const PartManifest& first = parts.begin()->second.second;
  for (const auto& [k, entry] : parts) {
    const RunIdentity& id = entry.second.identity;
    for (std::size_t i = 0; i < std::max(id.size(), first.identity.size()); ++i) {
      const bool same = i < id.size() && i < first.identity.size() && id[i] == first.identity[i];
      if (same) continue;
      const std::string key = i < first.identity.size() ? first.identity[i].first : id[i].first;
      return Error{"cannot merge: " + describePart({k, n}) + " is from another run than part 1: its " + key + " is \"" +
                   (i < id.size() ? id[i].second : std::string()) + "\", part 1's \"" +
                   (i < first.identity.size() ? first.identity[i].second : std::string()) +
                   "\". Re-run the parts of one run (same tool, city and options). Nothing was published."};
    }
  }
  const std::string city = cityManifestIdentity(tileset);
  for (const auto& [key, value] : first.identity) {
    if (key == "city" && value != city) {
      return Error{"cannot merge: the city changed since its parts were made (" + value + " then, " + city +
                   " now); run the parts again. Nothing was published."};
    }
  }
  // Every leaf of the city exactly once, as assignParts gives it.
  const auto expected = assignParts(tileset, n);
  for (const auto& [k, entry] : parts) {
    std::vector<std::uint32_t> nodes;
    for (const PartLeafEntry& e : entry.second.leaves) nodes.push_back(e.node);
    if (nodes != expected[k - 1]) {
      return Error{"cannot merge: " + describePart({k, n}) + " holds other tiles than the city's part " +
                   std::to_string(k) + " (" + std::to_string(nodes.size()) + " leaves, expected " +
                   std::to_string(expected[k - 1].size()) + "); re-run it"};
    }
  }

  // Complete: every leaf file is there with its size and CRC (checked on every core, each file read
  // through a small buffer: the histories are most of the response's bytes); the first bad file in
  // part and leaf order is named.
  {
    struct Check {
      const std::string* folder;
      const std::string* file;
      std::uint64_t bytes;
      std::uint32_t crc;
      unsigned part;
    };
    std::vector<Check> checks;
    for (const auto& [k, entry] : parts) {
      for (const PartLeafEntry& e : entry.second.leaves) {
        checks.push_back({&entry.first, &e.files.summaryFile, e.files.summaryBytes, e.files.summaryCrc32, k});
        checks.push_back({&entry.first, &e.files.historyFile, e.files.historyBytes, e.files.historyCrc32, k});
      }
    }
    std::vector<std::string> problems(checks.size());
    parallelFor(checks.size(), threads, [&](std::size_t i) {
      const Check& c = checks[i];
      const std::string label = describePart({c.part, n}) + " (" + *c.folder + ")";
      const std::string path = *c.folder + "/" + *c.file;
      auto digest = fileDigest(path);
      if (!digest.ok()) {
        problems[i] = label + " is incomplete: " + digest.error();
      } else if (digest->bytes != c.bytes || digest->crc32 != c.crc) {
        problems[i] = damagedPartFile(label, path, *digest, c.bytes, c.crc);
      }
    });
    if (interrupted()) return Error{"interrupted; the city's previous response is unchanged"};
    for (const std::string& problem : problems) {
      if (!problem.empty()) return Error{problem};
    }
  }
  // The results and notes of every part.
  std::vector<PartResults> results(n);
  std::vector<ResponseNotes> notes(n);
  for (const auto& [k, entry] : parts) {
    const std::string& folder = entry.first;
    const PartManifest& m = entry.second;
    const std::string label = describePart(m.shard) + " (" + folder + ")";
    auto stored = readPartFile(folder, m.results.file, m.results.bytes, m.results.crc32, label);
    if (!stored.ok()) return Error{stored.error()};
    auto raw = unpackStoredFile(*stored, folder + "/" + m.results.file);
    if (!raw.ok()) return Error{raw.error()};
    auto decoded = decodePartResults(*raw, folder + "/" + m.results.file);
    if (!decoded.ok()) return Error{decoded.error()};
    results[k - 1] = std::move(decoded).value();
    auto notesBytes = readPartFile(folder, m.notes.file, m.notes.bytes, m.notes.crc32, label);
    if (!notesBytes.ok()) return Error{notesBytes.error()};
    auto parsedNotes =
        parseResponseNotes(std::string_view(reinterpret_cast<const char*>(notesBytes->data()), notesBytes->size()),
                           folder + "/notes.json");
    if (!parsedNotes.ok()) return Error{parsedNotes.error()};
    notes[k - 1] = std::move(parsedNotes).value();
  }
  // The run's description (every part's is the same: the same run).
  const std::string& firstFolder = parts.begin()->second.first;
  auto infoBytes = readPartFile(firstFolder, first.info.file, first.info.bytes, first.info.crc32, "part 1");
  if (!infoBytes.ok()) return Error{infoBytes.error()};
  auto described = parseTileset(std::string_view(reinterpret_cast<const char*>(infoBytes->data()), infoBytes->size()),
                                firstFolder + "/" + first.info.file);
  if (!described.ok()) return Error{described.error()};
  if (!described->response) return Error{firstFolder + "/" + first.info.file + ": no response description"};
  std::optional<Districts> districts;
  if (first.districts) {
    auto bytes =
        readPartFile(firstFolder, first.districts->file, first.districts->bytes, first.districts->crc32, "part 1");
    if (!bytes.ok()) return Error{bytes.error()};
    auto d = parseDistricts(std::string_view(reinterpret_cast<const char*>(bytes->data()), bytes->size()),
                            firstFolder + "/" + first.districts->file);
    if (!d.ok()) return Error{d.error()};
    districts = std::move(d).value();
  }

  // Publish: the leaves linked into a new response folder, their results remembered for the inner
  // tiles, then the same finish as a one-machine run.
  if (first.scenario != scenario) {
    return Error{staging + " holds parts of scenario " + std::to_string(first.scenario) + ", not " +
                 std::to_string(scenario)};
  }
  auto writer = ResponseWriter::create(dir, tileset);
  if (!writer.ok()) return Error{writer.error()};
  if (scenario > 0) (*writer)->setScenario(scenario, first.scenarioNames);
  ResponseRunReport report;
  report.parts = n;
  detail::FinishInputs finish;
  finish.info = *described->response;
  finish.leafRates.resize(tileset.nodes.size());
  finish.districts = districts ? &*districts : nullptr;
  finish.population = first.population;
  // The leaves of every part adopted on every core (each tile read again for its buildings' ids);
  // the writer's bookkeeping does not depend on their order. A failed leaf stops the others from
  // starting and its message is returned (with several bad leaves, not always the first in order).
  struct Leaf {
    unsigned part;
    std::size_t index;
  };
  std::vector<Leaf> leaves;
  for (const auto& [k, entry] : parts) {
    const PartManifest& m = entry.second;
    const PartResults& r = results[k - 1];
    const std::string& folder = entry.first;
    if (r.leafSummaries.size() != m.leaves.size()) {
      return Error{folder + "/" + m.results.file + ": " + std::to_string(r.leafSummaries.size()) +
                   " leaves, part.json lists " + std::to_string(m.leaves.size())};
    }
    for (std::size_t i = 0; i < m.leaves.size(); ++i) {
      if (r.leafSummaries[i].first != m.leaves[i].node)
        return Error{folder + "/" + m.results.file + ": leaves out of order"};
      leaves.push_back({k, i});
    }
  }
  Progress progress("merging " + std::to_string(n) + " parts", leaves.size());
  std::mutex progressMutex;
  std::uint64_t done = 0;
  std::vector<std::string> problems(leaves.size());
  std::atomic<bool> failed{false};
  parallelFor(leaves.size(), threads, [&](std::size_t j) {
    if (failed) return;
    const Failure fail{problems[j], failed};
    const auto& [folder, m] = parts.at(leaves[j].part);
    PartResults& r = results[leaves[j].part - 1];
    const std::size_t i = leaves[j].index;
    const PartLeafEntry& e = m.leaves[i];
    const std::string relative = stagingFolder(scenario) + "/" + partFolderName(m.shard);
    const TileNode& node = tileset.nodes[e.node];
    auto bytes = readFile(dir + "/" + node.file);
    if (!bytes.ok()) return fail(bytes.error());
    auto tile = decodeCityTile(*bytes, dir + "/" + node.file);
    if (!tile.ok()) return fail(tile.error());
    auto summary = decodeResponseSummary(r.leafSummaries[i].second, folder + "/" + m.results.file);
    if (!summary.ok()) return fail(summary.error());
    std::vector<BuildingResult> buildings = resultsFromSummary(*summary);
    if (buildings.size() != tile->buildings.size()) {
      return fail(folder + ": leaf " + node.key() + " has " + std::to_string(buildings.size()) +
                  " results for the tile's " + std::to_string(tile->buildings.size()) + " buildings");
    }
    r.leafSummaries[i].second = {};
    TileResponseFiles files = e.files;
    files.summaryFile = relative + "/" + e.files.summaryFile;
    files.historyFile = relative + "/" + e.files.historyFile;
    if (Status s = (*writer)->adoptLeaf(e.node, files, *tile, buildings, e.stats); !s.ok()) {
      return fail(s.error());
    }
    finish.leafRates[e.node] = e.rate;
    const std::lock_guard lock(progressMutex);
    progress.update(++done);
  });
  if (interrupted()) return Error{"interrupted; the city's previous response is unchanged"};
  for (const std::string& problem : problems) {
    if (!problem.empty()) return Error{problem};
  }
  for (const auto& [k, entry] : parts) {
    const PartManifest& m = entry.second;
    PartResults& r = results[k - 1];
    (*writer)->addNotes(notes[k - 1]);
    for (PartLoss& l : r.losses) {
      finish.losses.losses.push_back(l.loss);
      finish.losses.key.push_back(l.key);
      finish.losses.classes.push_back(l.lossClass);
      if (districts) finish.losses.district.push_back(l.district);
    }
    r.losses = {};
    const ResponseRunReport& p = m.report;
    report.buildings += p.buildings;
    report.solveSeconds += p.solveSeconds;
    report.passOneSeconds += p.passOneSeconds;
    report.passTwoSeconds += p.passTwoSeconds;
    report.encodeSeconds += p.encodeSeconds;
    report.lossSeconds += p.lossSeconds;
    report.storeySteps += p.storeySteps;
    report.nonConvergedSteps += p.nonConvergedSteps;
    report.encodingAttempts += p.encodingAttempts;
    report.outsideGrid += p.outsideGrid;
    report.worstRelativeError = std::max(report.worstRelativeError, p.worstRelativeError);
    report.p99RelativeError = std::max(report.p99RelativeError, p.p99RelativeError);
  }
  progress.finish();
  const ResponseInfo& info = *described->response;
  report.motion = info.motion;
  report.scenario = info.scenario;
  report.eventType = info.eventType;
  report.records = info.records.size();
  report.scaling = first.report.scaling;
  report.frames = first.report.frames;
  report.timeStepS = first.report.timeStepS;
  if (Status s = detail::finishResponse(**writer, std::move(finish), report); !s.ok()) return Error{s.error()};
  removeTree(staging);
  if (scenario > 0)
    ::rmdir((dir + "/" + std::string(kStagingFolder)).c_str());  // when no other scenario's parts are there
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace qv::prep
