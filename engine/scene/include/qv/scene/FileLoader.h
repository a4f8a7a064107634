// FileLoader: the one fetch -> verify -> decode -> retry state machine of every file the scene
// loads: city tiles, their response summaries and histories, the search index and the city-wide
// response summary.
//
// A file is fetched with a time limit that grows with its size and its failures, checked against
// the size and CRC-32 the manifest promises, then handed to the caller, who decodes it now, later
// (tiles, under the frame's work budget) or rejects it. A failure waits before the file is fetched
// again (backoff: 1 s doubling to 30 s for what may recover soon, 30 s for what only a fixed server
// brings back) and is reported once, as a LoadError keyed by the file's URL; when the file loads
// at last, its error is withdrawn by that key. Requests in flight are counted here, for the
// scene's one limit. Completions arrive through the Fetcher's poll(), on the frame loop's thread.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "qv/lod/TileSelector.h"
#include "qv/scene/Fetcher.h"
#include "qv/scene/SceneClock.h"

namespace qv {

enum class FileKind : std::uint8_t {
  Manifest,
  Tile,
  ResponseSummary,
  ResponseHistory,
  SearchIndex,
  CitySummary,
  Consequences,
  Ground,  ///< a ground tile (the map under the city)
};

/// A file that failed, as the viewer shows it until the file loads.
struct LoadError {
  FileKind kind = FileKind::Tile;
  std::string key;      ///< the file's URL: what the error is withdrawn by; empty: never withdrawn
  std::string message;  ///< the text shown, naming the file and what is wrong
};

/// A file as the manifest describes it.
struct FileSpec {
  FileKind kind = FileKind::Tile;
  std::string url;          ///< resolved against the manifest's URL
  std::uint64_t bytes = 0;  ///< the size the manifest promises
  std::uint32_t crc32 = 0;  ///< the CRC-32 the manifest promises
  std::string tileKey;      ///< Tile: its key ("2/1/3"), which its messages name
};

/// One file's loading state; owned by the caller, who keeps it alive (and at the same address)
/// while a request for it is in flight, or cancels it first.
struct FileLoad {
  TileState state = TileState::Unloaded;
  Fetcher::RequestId request = 0;  ///< in flight, 0 when none
  int failures = 0;                ///< since it last loaded
  double retryAt = 0.0;            ///< clock seconds before which it is not fetched again
  bool errorShown = false;         ///< its error was reported and not withdrawn yet
};

/// The caller's verdict on bytes that match the manifest.
struct Verdict {
  enum class Outcome : std::uint8_t { Loaded, Later, Rejected };
  Outcome outcome = Outcome::Loaded;
  std::string problem;     ///< Rejected: what is wrong, naming the file
  bool transient = false;  ///< Rejected: worth retrying soon
  static Verdict loaded() { return {}; }
  /// The caller decides later, with FileLoader::succeed or fail.
  static Verdict later() { return {Outcome::Later, {}, false}; }
  static Verdict rejected(std::string problem, bool transient) {
    return {Outcome::Rejected, std::move(problem), transient};
  }
};

struct FileLoaderOptions {
  std::uint32_t maxRequestsInFlight = 16;
  std::uint32_t requestTimeoutMs = 20000;            ///< CitySceneOptions::requestTimeoutMs
  std::uint32_t slowestBytesPerSecond = 256u << 10;  ///< CitySceneOptions::slowestBytesPerSecond
};

/// Seconds to wait after the n-th consecutive failure (n >= 1): 1 s doubling to 30 s when
/// `transient`, else 30 s.
double backoffSeconds(int failures, bool transient);
/// HTTP statuses worth retrying soon (0: no response; 408, 429, 5xx).
bool transientStatus(int status);
/// Why a response failed, as messages say it: "HTTP 503", or the fetcher's error without a status.
std::string responseProblem(const FetchResponse& response);
/// A request's time limit (ms) for a file of `bytes` after `failures` failures:
/// (requestTimeoutMs + bytes at slowestBytesPerSecond) doubled per failure up to 8x, at most 30 min.
std::uint32_t requestTimeoutMs(const FileLoaderOptions& options, std::uint64_t bytes, int failures);

class FileLoader {
 public:
  /// Decides about verified bytes (may keep them by moving them out).
  using Accept = std::function<Verdict(std::vector<std::uint8_t>& bytes)>;
  using ErrorSink = std::function<void(const LoadError&)>;
  using ResolvedSink = std::function<void(const std::string& key)>;

  FileLoader(Fetcher& fetcher, const SceneClock& clock, ErrorSink onError);
  FileLoader(const FileLoader&) = delete;
  FileLoader& operator=(const FileLoader&) = delete;

  void setResolvedSink(ResolvedSink sink) { onResolved_ = std::move(sink); }
  FileLoaderOptions& options() { return options_; }

  [[nodiscard]] std::uint32_t inFlight() const { return inFlight_; }
  /// Below the limit of requests in flight.
  [[nodiscard]] bool hasRoom() const { return inFlight_ < options_.maxRequestsInFlight; }
  /// Not loading or loaded, and its backoff (if it failed) has passed.
  [[nodiscard]] bool due(const FileLoad& load) const;

  /// Fetches `spec` into `load` when due (the caller checks hasRoom where the limit applies);
  /// false when not due. `accept` runs on verified bytes; `onFailure` after every failure of this
  /// request (its fetch, its check or its verdict), before the error is reported.
  bool start(FileLoad& load, const FileSpec& spec, Accept accept, std::function<void()> onFailure = {});
  /// A file accepted with Verdict::later has loaded: its error, if shown, is withdrawn.
  void succeed(FileLoad& load, const FileSpec& spec);
  /// A file accepted with Verdict::later (or loaded) is unusable after all: `problem` names it.
  void fail(FileLoad& load, const FileSpec& spec, const std::string& problem, bool transient);
  /// Drops the completion of the request in flight for `load`, if any.
  void cancel(FileLoad& load);
  /// A failed file no longer needed: back to Unloaded (its backoff kept: `failures` stays), its
  /// error withdrawn; requested again when needed, and reported again if it fails again.
  void forget(FileLoad& load, const FileSpec& spec);
  /// A plain request counted in flight (the manifest, whose failures the caller reports).
  Fetcher::RequestId fetch(const std::string& url, Fetcher::Done done, std::uint32_t timeoutMs);

 private:
  void onResponse(FileLoad& load, const FileSpec& spec, FetchResponse response, const Accept& accept,
                  const std::function<void()>& onFailure);
  void failed(FileLoad& load, const FileSpec& spec, std::string message, bool transient);

  Fetcher& fetcher_;
  const SceneClock& clock_;
  ErrorSink onError_;
  ResolvedSink onResolved_;
  FileLoaderOptions options_;
  std::uint32_t inFlight_ = 0;
};

}  // namespace qv
