// CityScenarios: the scenario catalogue of the open city (scenarios.json beside its manifest,
// qv/format/ScenarioCatalogue.h) and what is known of each scenario's manifest: whether it is
// there yet, and its event type once read. The Viewer owns one per city folder (kept while it
// switches between the folder's scenarios) and switches by opening another manifest.
//
// Loading never throws and never stops the city: a missing catalogue (HTTP 404, or no response at
// all: another origin may answer a 404 without a CORS header) means the city has none, without a
// message; any other failure, or a file that is no catalogue, is reported once
// (keyed by the catalogue's address) and the city goes on without scenarios. Bad entries are left
// out, each reported (ScenarioCatalogue::warnings).
//
// Completions arrive through the Fetcher's poll() (the city scene polls it every frame), on the
// frame loop's thread; callbacks only record what arrived.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "qv/format/ScenarioCatalogue.h"
#include "qv/format/Tileset.h"
#include "qv/scene/Fetcher.h"

namespace qv {

/// What is known of one scenario's manifest.
enum class ScenarioState : std::uint8_t {
  Unchecked,  ///< not fetched yet (beyond the checks made on their own, or not come to yet)
  Checking,   ///< its manifest is being fetched
  Ready,      ///< its manifest loaded and is a valid manifest (or it is the open one)
  NotReady,   ///< its manifest is not there yet (HTTP 404)
  Broken,     ///< its manifest failed otherwise (HTTP error, network) or is not a valid manifest
};

/// "not checked", "checking", "ready", "not ready", "broken": the JS API's words.
const char* scenarioStateName(ScenarioState state);

struct ScenarioStatus {
  ScenarioEntry entry;
  ScenarioState state = ScenarioState::Unchecked;
  /// Ready: the response's event type, "SCENARIO", "ACTUAL", or "" (not stated, or no response).
  std::string eventType;
  /// Ready: the response's earthquake ("M6.6 at -74.005,40.705, depth 8 km"), or "".
  std::string earthquake;
  bool hasResponse = false;  ///< Ready: the manifest has earthquake results
  /// Ready: the same results as the open manifest (the same response files, by name and CRC-32),
  /// though another file: tileset.json when it is a copy of this scenario's manifest.
  bool sameResultsAsOpen = false;
  std::string problem;  ///< NotReady, Broken: why, for the panel ("HTTP 404", the parser's message)
};

class CityScenarios {
 public:
  enum class CatalogueState : std::uint8_t {
    Loading,  ///< scenarios.json requested
    Absent,   ///< HTTP 404: the city has no catalogue
    Loaded,   ///< parsed (possibly with entries left out)
    Failed,   ///< another failure, or not a catalogue: reported
  };
  /// A message for the viewer, keyed by the address it is about (withdrawn by that key).
  using ErrorSink = std::function<void(const std::string& message, const std::string& key)>;
  /// How many manifests checkNext() fetches on its own, at most: a catalogue of a thousand
  /// scenarios must not make the viewer download a thousand manifests. Others are checked when
  /// chosen (check()).
  static constexpr std::size_t kMaxAutomaticChecks = 32;

  /// Requests scenarios.json beside `manifestUrl` (resolveUrl) through `fetcher`, which is not
  /// owned and must outlive this; requests time out after `timeoutMs`.
  CityScenarios(Fetcher& fetcher, const std::string& manifestUrl, ErrorSink onError, std::uint32_t timeoutMs = 20000);
  ~CityScenarios();  ///< cancels the requests in flight
  CityScenarios(const CityScenarios&) = delete;
  CityScenarios& operator=(const CityScenarios&) = delete;

  [[nodiscard]] CatalogueState state() const { return state_; }
  /// True once the catalogue has loaded with at least one scenario: the panel shows the section.
  [[nodiscard]] bool available() const { return state_ == CatalogueState::Loaded && !scenarios_.empty(); }
  [[nodiscard]] const std::string& catalogueUrl() const { return catalogueUrl_; }
  /// In the catalogue's order (empty until it has loaded).
  [[nodiscard]] const std::vector<ScenarioStatus>& scenarios() const { return scenarios_; }
  /// The scenario with this index, or nullptr.
  [[nodiscard]] const ScenarioStatus* find(std::uint32_t index) const;
  /// The scenario whose manifest is the open one (by file name, setOpen), or nullptr: also when
  /// the open manifest (tileset.json) is not listed.
  [[nodiscard]] const ScenarioStatus* current() const;
  /// The file name of the open manifest ("tileset.json", "scenario-2.json").
  [[nodiscard]] const std::string& openFileName() const { return openFile_; }
  /// The address of a scenario's manifest: beside the catalogue.
  [[nodiscard]] std::string manifestUrl(const ScenarioEntry& entry) const;

  /// The manifest now open (its address) and, once loaded, what it holds (nullptr before): its
  /// scenario is Ready with its event type, and the others are compared with it.
  void setOpen(const std::string& manifestUrl, const Tileset* tileset);
  /// Fetches the next Unchecked scenario's manifest (in the catalogue's order) when nothing is in
  /// flight, up to kMaxAutomaticChecks in all. The viewer calls it once its view has loaded.
  void checkNext();
  /// Fetches scenario `index`'s manifest now, also when it was checked before (it may have been
  /// written since), unless it is being fetched. False when there is no such scenario.
  bool check(std::uint32_t index);

 private:
  void onCatalogue(FetchResponse response);
  void onManifest(std::size_t at, FetchResponse response);
  void fetchManifest(std::size_t at);
  void compareWithOpen();

  Fetcher& fetcher_;
  ErrorSink onError_;
  std::uint32_t timeoutMs_;
  std::string catalogueUrl_;
  CatalogueState state_ = CatalogueState::Loading;
  Fetcher::RequestId catalogueRequest_ = 0;
  std::vector<ScenarioStatus> scenarios_;
  std::vector<Fetcher::RequestId> requests_;  // of scenarios_, same order; 0: none in flight
  std::vector<std::string> resultsKeys_;      // of scenarios_: the response files of a Ready one
  std::string openFile_;
  std::string openResultsKey_;
  std::string openEventType_, openEarthquake_;
  bool openLoaded_ = false;
  bool openHasResponse_ = false;
  std::size_t automaticChecks_ = 0;
};

}  // namespace qv
