// Asynchronous HTTP GET, as the scene needs it. The browser platform implements it with
// emscripten_fetch; tests and benchmarks use in-memory or file-backed fakes.
//
// Contract: fetch() never calls `done` from inside itself; completions are delivered later, on
// the frame loop's thread, through poll(). Every request completes exactly once (success, HTTP
// error, network error or timeout), unless cancelled.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace qv {

struct FetchResponse {
  int status = 0;                   ///< HTTP status; 0 when the request failed before a response
  std::vector<std::uint8_t> bytes;  ///< the body (of any status)
  std::string error;                ///< why it failed, when status is 0 ("timeout", "network error")
  [[nodiscard]] bool ok() const { return status >= 200 && status < 300; }
};

class Fetcher {
 public:
  using Done = std::function<void(FetchResponse)>;
  using RequestId = std::uint64_t;

  virtual ~Fetcher() = default;
  /// Starts a GET of `url` (absolute, or relative to the page). `timeoutMs` 0: no timeout.
  virtual RequestId fetch(const std::string& url, Done done, std::uint32_t timeoutMs) = 0;
  /// Drops a request's completion (the request may still run).
  virtual void cancel(RequestId id) = 0;
  /// Delivers the completions that arrived since the last poll.
  virtual void poll() = 0;
};

/// Resolves `relative` against the URL of the file it appears in (`base`): "a/b/tileset.json" +
/// "tiles/0.qvt" -> "a/b/tiles/0.qvt". Absolute URLs and paths in `relative` are returned as is.
std::string resolveUrl(const std::string& base, const std::string& relative);

/// Why `url` cannot be a city's address (the page's ?data=), or empty when it can: only paths on
/// this site and http(s) URLs are fetched; other schemes (javascript:, file:, data:, ...) and
/// empty or over-long addresses are refused before any request.
std::string dataUrlProblem(const std::string& url);

/// The data origin policy of a deployment. A link can put any address in the page's ?data=, but a
/// site shows only cities from its own origin and from the origins its administrator lists in
/// config.json beside index.html (web/quakeview.js reads it; README, "Deploying"): otherwise a
/// link to the official viewer could show fabricated damage under the city's own address.
/// Origins are as the browser serializes them ("https://data.example.org", "http://127.0.0.1:8080").
struct DataOriginPolicy {
  std::string pageOrigin;                   ///< the page's origin; empty: no policy (native use, tests)
  std::vector<std::string> allowedOrigins;  ///< other origins the site allows
  std::string urlOrigin;                    ///< the origin the browser resolves the city's address to
};

/// Why the city may not be loaded under `policy` (a message naming the origin and how to allow it),
/// or empty when it may: no policy, the page's own origin, or an allowed one.
std::string dataOriginProblem(const DataOriginPolicy& policy);

/// Where an allowed city comes from, as the panel says it: "this site (http://127.0.0.1:8080)" or
/// "https://data.example.org (allowed by this site's config.json)"; empty without a policy.
std::string dataOriginDescription(const DataOriginPolicy& policy);

/// True when `url` names another site (an absolute http(s) URL), whose server must allow the page
/// to read its files (CORS) for a request to succeed.
bool isAbsoluteHttpUrl(const std::string& url);

}  // namespace qv
