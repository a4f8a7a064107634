#include "qv/scene/CityScenarios.h"

#include "qv/scene/FileLoader.h"

namespace qv {
namespace {

/// What identifies a manifest's results: its response files' names and CRC-32s (the root tile's
/// summary and the city-wide summary); "" without results.
std::string resultsKey(const Tileset& tileset) {
  if (!tileset.response) return {};
  std::string key = std::to_string(tileset.response->durationSeconds);
  if (!tileset.nodes.empty() && tileset.nodes[0].response) {
    const TileResponseFiles& r = *tileset.nodes[0].response;
    key += "|" + r.summaryFile + "|" + std::to_string(r.summaryCrc32) + "|" + std::to_string(r.summaryBytes);
  }
  if (const auto& index = tileset.response->summaryIndex) {
    key += "|" + index->file + "|" + std::to_string(index->crc32) + "|" + std::to_string(index->bytes);
  }
  return key;
}

}  // namespace

const char* scenarioStateName(ScenarioState state) {
  switch (state) {
    case ScenarioState::Unchecked:
      return "not checked";
    case ScenarioState::Checking:
      return "checking";
    case ScenarioState::Ready:
      return "ready";
    case ScenarioState::NotReady:
      return "not ready";
    case ScenarioState::Broken:
      return "broken";
  }
  return "not checked";
}

CityScenarios::CityScenarios(Fetcher& fetcher, const std::string& manifestUrl, ErrorSink onError,
                             std::uint32_t timeoutMs)
    : fetcher_(fetcher),
      onError_(std::move(onError)),
      timeoutMs_(timeoutMs),
      catalogueUrl_(resolveUrl(manifestUrl, std::string(kScenarioCatalogueFile))),
      openFile_(urlFileName(manifestUrl)) {
  catalogueRequest_ = fetcher_.fetch(
      catalogueUrl_, [this](FetchResponse r) { onCatalogue(std::move(r)); }, timeoutMs_);
}

CityScenarios::~CityScenarios() {
  if (catalogueRequest_ != 0) fetcher_.cancel(catalogueRequest_);
  for (const Fetcher::RequestId id : requests_) {
    if (id != 0) fetcher_.cancel(id);
  }
}

void CityScenarios::onCatalogue(FetchResponse response) {
  catalogueRequest_ = 0;
  // A city without scenarios: nothing to say. A request that got no response at all counts the
  // same: a city on another origin is often served so that a missing file's 404 carries no CORS
  // header, which the browser reports as a network error; a real outage shows in the city's own
  // files, which are reported.
  if (response.status == 404 || response.status == 0) {
    state_ = CatalogueState::Absent;
    return;
  }
  if (!response.ok()) {
    state_ = CatalogueState::Failed;
    onError_("The city's scenario list " + catalogueUrl_ + " could not be loaded (" + responseProblem(response) +
                 "); only the scenario opened is shown.",
             catalogueUrl_);
    return;
  }
  const std::string_view text(reinterpret_cast<const char*>(response.bytes.data()), response.bytes.size());
  Result<ScenarioCatalogue> parsed = parseScenarioCatalogue(text, catalogueUrl_);
  if (!parsed.ok()) {
    state_ = CatalogueState::Failed;
    onError_("The city's scenario list was refused: " + parsed.error() + ". Only the scenario opened is shown.",
             catalogueUrl_);
    return;
  }
  state_ = CatalogueState::Loaded;
  for (const std::string& warning : parsed->warnings) onError_("Scenario list: " + warning + ".", catalogueUrl_);
  for (ScenarioEntry& entry : parsed->scenarios) {
    ScenarioStatus s;
    s.entry = std::move(entry);
    scenarios_.push_back(std::move(s));
  }
  requests_.assign(scenarios_.size(), 0);
  resultsKeys_.assign(scenarios_.size(), std::string());
  compareWithOpen();
}

const ScenarioStatus* CityScenarios::find(std::uint32_t index) const {
  for (const ScenarioStatus& s : scenarios_) {
    if (s.entry.index == index) return &s;
  }
  return nullptr;
}

const ScenarioStatus* CityScenarios::current() const {
  for (const ScenarioStatus& s : scenarios_) {
    if (s.entry.manifest == openFile_) return &s;
  }
  return nullptr;
}

std::string CityScenarios::manifestUrl(const ScenarioEntry& entry) const {
  return resolveUrl(catalogueUrl_, entry.manifest);
}

void CityScenarios::setOpen(const std::string& manifestUrl, const Tileset* tileset) {
  openFile_ = std::string(urlFileName(manifestUrl));
  openLoaded_ = tileset != nullptr;
  openResultsKey_ = tileset != nullptr ? resultsKey(*tileset) : std::string();
  openHasResponse_ = tileset != nullptr && tileset->response.has_value();
  openEventType_ = openHasResponse_ ? tileset->response->eventType : std::string();
  openEarthquake_ = openHasResponse_ ? tileset->response->scenario : std::string();
  compareWithOpen();
}

void CityScenarios::compareWithOpen() {
  for (std::size_t i = 0; i < scenarios_.size(); ++i) {
    ScenarioStatus& s = scenarios_[i];
    if (s.entry.manifest == openFile_ && openLoaded_) {
      // The open manifest: what it holds is known without fetching it again.
      if (requests_[i] != 0) fetcher_.cancel(requests_[i]);
      requests_[i] = 0;
      s.state = ScenarioState::Ready;
      s.problem.clear();
      s.eventType = openEventType_;
      s.earthquake = openEarthquake_;
      s.hasResponse = openHasResponse_;
      resultsKeys_[i] = openResultsKey_;
    }
    s.sameResultsAsOpen = s.entry.manifest != openFile_ && s.state == ScenarioState::Ready &&
                          !openResultsKey_.empty() && resultsKeys_[i] == openResultsKey_;
  }
}

void CityScenarios::checkNext() {
  if (state_ != CatalogueState::Loaded || automaticChecks_ >= kMaxAutomaticChecks) return;
  for (const Fetcher::RequestId id : requests_) {
    if (id != 0) return;  // one at a time: the city's own files come first
  }
  for (std::size_t i = 0; i < scenarios_.size(); ++i) {
    if (scenarios_[i].state != ScenarioState::Unchecked) continue;
    ++automaticChecks_;
    fetchManifest(i);
    return;
  }
}

bool CityScenarios::check(std::uint32_t index) {
  for (std::size_t i = 0; i < scenarios_.size(); ++i) {
    if (scenarios_[i].entry.index != index) continue;
    if (requests_[i] == 0) fetchManifest(i);
    return true;
  }
  return false;
}

void CityScenarios::fetchManifest(std::size_t at) {
  scenarios_[at].state = ScenarioState::Checking;
  // Manifests of large cities run to megabytes: a longer limit than the catalogue's.
  requests_[at] = fetcher_.fetch(
      manifestUrl(scenarios_[at].entry), [this, at](FetchResponse r) { onManifest(at, std::move(r)); }, timeoutMs_ * 3);
}

void CityScenarios::onManifest(std::size_t at, FetchResponse response) {
  requests_[at] = 0;
  ScenarioStatus& s = scenarios_[at];
  s.problem.clear();
  s.eventType.clear();
  s.earthquake.clear();
  s.hasResponse = false;
  resultsKeys_[at].clear();
  if (response.status == 404) {
    s.state = ScenarioState::NotReady;
    s.problem = s.entry.manifest + " is not there yet (HTTP 404)";
  } else if (!response.ok()) {
    s.state = ScenarioState::Broken;
    s.problem = s.entry.manifest + " could not be loaded (" + responseProblem(response) + ")";
  } else {
    const std::string_view text(reinterpret_cast<const char*>(response.bytes.data()), response.bytes.size());
    Result<Tileset> parsed = parseTileset(text, s.entry.manifest);
    if (!parsed.ok()) {
      s.state = ScenarioState::Broken;
      s.problem = parsed.error();
    } else {
      s.state = ScenarioState::Ready;
      s.hasResponse = parsed->response.has_value();
      if (s.hasResponse) {
        s.eventType = parsed->response->eventType;
        s.earthquake = parsed->response->scenario;
      }
      resultsKeys_[at] = resultsKey(*parsed);
    }
  }
  compareWithOpen();
}

}  // namespace qv
