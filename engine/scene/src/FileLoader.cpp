#include "qv/scene/FileLoader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "qv/core/Crc32.h"

namespace qv {
namespace {

std::string hex32(std::uint32_t v) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "%08x", v);
  return buffer;
}

// How messages name a file of this kind ("Response summary city/r/0.qvs").
std::string subject(const FileSpec& spec) {
  switch (spec.kind) {
    case FileKind::Manifest:
      return "City " + spec.url;
    case FileKind::Tile:
      return "Tile " + spec.tileKey;
    case FileKind::ResponseSummary:
    case FileKind::CitySummary:
      return "Response summary " + spec.url;
    case FileKind::ResponseHistory:
      return "Response history " + spec.url;
    case FileKind::SearchIndex:
      return "Search index " + spec.url;
    case FileKind::Consequences:
      return "Consequences " + spec.url;
    case FileKind::Ground:
      return "Ground tile " + spec.url;
  }
  return spec.url;
}

// A failed fetch, as reported. A tile's messages name its key and then the URL.
std::string fetchProblem(const FileSpec& spec, const FetchResponse& response) {
  if (spec.kind == FileKind::Tile) return subject(spec) + " failed: " + spec.url + ": " + responseProblem(response);
  return subject(spec) + " failed: " + responseProblem(response);
}

// Bytes that are not what the manifest promises (truncated, corrupt, or a stale cached copy).
std::string checksumProblem(const FileSpec& spec, const std::vector<std::uint8_t>& bytes) {
  if (spec.kind != FileKind::Tile) return subject(spec) + " failed: size or checksum differs from the manifest";
  return subject(spec) + " failed: " + spec.url + ": " + std::to_string(bytes.size()) + " bytes with CRC-32 " +
         hex32(crc32(bytes)) + ", the manifest says " + std::to_string(spec.bytes) + " bytes, " + hex32(spec.crc32) +
         " (truncated, corrupt or stale)";
}

// Whether a failed fetch may recover soon. Response summaries and histories retry every failed
// fetch after the short backoff (a 404 included), the other files only the statuses that may
// recover: kept as the scene always did.
bool fetchFailureTransient(const FileSpec& spec, const FetchResponse& response) {
  if (spec.kind == FileKind::ResponseSummary || spec.kind == FileKind::ResponseHistory) return true;
  return transientStatus(response.status);
}

}  // namespace

double backoffSeconds(int failures, bool transient) {
  return transient ? std::min(30.0, std::pow(2.0, std::min(std::max(failures, 1) - 1, 5))) : 30.0;
}

bool transientStatus(int status) {
  return status == 0 || status == 408 || status == 429 || status >= 500;
}

std::string responseProblem(const FetchResponse& response) {
  return response.status == 0 ? response.error : "HTTP " + std::to_string(response.status);
}

std::uint32_t requestTimeoutMs(const FileLoaderOptions& options, std::uint64_t bytes, int failures) {
  const double rate = std::max<double>(options.slowestBytesPerSecond, 1.0);
  const double ms = (static_cast<double>(options.requestTimeoutMs) + static_cast<double>(bytes) * 1000.0 / rate) *
                    static_cast<double>(1 << std::clamp(failures, 0, 3));
  return static_cast<std::uint32_t>(std::min(ms, 30.0 * 60.0 * 1000.0));
}

FileLoader::FileLoader(Fetcher& fetcher, const SceneClock& clock, ErrorSink onError)
    : fetcher_(fetcher), clock_(clock), onError_(std::move(onError)) {}

bool FileLoader::due(const FileLoad& load) const {
  return (load.state == TileState::Unloaded || load.state == TileState::Failed) && load.retryAt <= clock_.nowSeconds();
}

bool FileLoader::start(FileLoad& load, const FileSpec& spec, Accept accept, std::function<void()> onFailure) {
  if (!due(load)) return false;
  load.state = TileState::Loading;
  ++inFlight_;
  load.request = fetcher_.fetch(
      spec.url,
      [this, &load, spec, accept = std::move(accept), onFailure = std::move(onFailure)](FetchResponse r) {
        --inFlight_;
        load.request = 0;
        onResponse(load, spec, std::move(r), accept, onFailure);
      },
      requestTimeoutMs(options_, spec.bytes, load.failures));
  return true;
}

void FileLoader::onResponse(FileLoad& load, const FileSpec& spec, FetchResponse response, const Accept& accept,
                            const std::function<void()>& onFailure) {
  std::string problem;
  bool transient = true;
  if (!response.ok()) {
    problem = fetchProblem(spec, response);
    transient = fetchFailureTransient(spec, response);
  } else if (response.bytes.size() != spec.bytes || crc32(response.bytes) != spec.crc32) {
    problem = checksumProblem(spec, response.bytes);
  } else {
    Verdict verdict = accept(response.bytes);
    if (verdict.outcome == Verdict::Outcome::Later) return;
    if (verdict.outcome == Verdict::Outcome::Loaded) {
      succeed(load, spec);
      return;
    }
    problem = spec.kind == FileKind::Tile ? subject(spec) + " failed: " + verdict.problem : std::move(verdict.problem);
    transient = verdict.transient;
  }
  load.state = TileState::Failed;  // before onFailure, which may look at it
  if (onFailure) onFailure();
  failed(load, spec, std::move(problem), transient);
}

void FileLoader::succeed(FileLoad& load, const FileSpec& spec) {
  load.state = TileState::Loaded;
  load.failures = 0;
  if (load.errorShown) {
    load.errorShown = false;
    if (onResolved_) onResolved_(spec.url);
  }
}

void FileLoader::fail(FileLoad& load, const FileSpec& spec, const std::string& problem, bool transient) {
  failed(load, spec, spec.kind == FileKind::Tile ? subject(spec) + " failed: " + problem : problem, transient);
}

void FileLoader::failed(FileLoad& load, const FileSpec& spec, std::string message, bool transient) {
  load.state = TileState::Failed;
  ++load.failures;
  load.retryAt = clock_.nowSeconds() + backoffSeconds(load.failures, transient);
  if (load.errorShown) return;  // reported once, until it loads
  load.errorShown = true;
  onError_(LoadError{spec.kind, spec.url, std::move(message)});
}

void FileLoader::forget(FileLoad& load, const FileSpec& spec) {
  if (load.state != TileState::Failed) return;
  load.state = TileState::Unloaded;
  if (load.errorShown) {
    load.errorShown = false;
    if (onResolved_) onResolved_(spec.url);
  }
}

void FileLoader::cancel(FileLoad& load) {
  if (load.request == 0) return;
  fetcher_.cancel(load.request);
  load.request = 0;
  --inFlight_;
}

Fetcher::RequestId FileLoader::fetch(const std::string& url, Fetcher::Done done, std::uint32_t timeoutMs) {
  ++inFlight_;
  return fetcher_.fetch(
      url,
      [this, done = std::move(done)](FetchResponse r) {
        --inFlight_;
        done(std::move(r));
      },
      timeoutMs);
}

}  // namespace qv
