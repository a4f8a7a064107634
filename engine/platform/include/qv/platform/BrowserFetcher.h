// Fetcher over emscripten_fetch (XMLHttpRequest into WASM memory). Completions arrive from the
// browser's event loop and are queued; poll() delivers them on the frame loop, so scene code never
// runs inside a browser callback.
#pragma once

#include <unordered_map>
#include <vector>

#include "qv/scene/Fetcher.h"

struct emscripten_fetch_t;

namespace qv {

class BrowserFetcher final : public Fetcher {
 public:
  BrowserFetcher() = default;
  ~BrowserFetcher() override;
  BrowserFetcher(const BrowserFetcher&) = delete;
  BrowserFetcher& operator=(const BrowserFetcher&) = delete;

  RequestId fetch(const std::string& url, Done done, std::uint32_t timeoutMs) override;
  void cancel(RequestId id) override;
  void poll() override;

  // Called from the emscripten_fetch callbacks.
  void complete(RequestId id, FetchResponse response);

 private:
  std::unordered_map<RequestId, Done> pending_;
  std::vector<std::pair<RequestId, FetchResponse>> completed_;
  RequestId nextId_ = 1;
};

}  // namespace qv
