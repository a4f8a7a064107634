#include "qv/platform/BrowserFetcher.h"

#include <emscripten/fetch.h>

#include <cstdint>
#include <cstring>

namespace qv {
namespace {

// The one fetcher of the app; callbacks find it through this pointer (emscripten_fetch's user
// data holds the request id).
BrowserFetcher* gFetcher = nullptr;

Fetcher::RequestId idOf(emscripten_fetch_t* f) {
  return static_cast<Fetcher::RequestId>(reinterpret_cast<std::uintptr_t>(f->userData));
}

void onSuccess(emscripten_fetch_t* f) {
  FetchResponse r;
  r.status = f->status;
  if (f->data != nullptr && f->numBytes > 0) {
    const auto* begin = reinterpret_cast<const std::uint8_t*>(f->data);
    r.bytes.assign(begin, begin + f->numBytes);
  }
  const auto id = idOf(f);
  emscripten_fetch_close(f);
  if (gFetcher != nullptr) gFetcher->complete(id, std::move(r));
}

void onError(emscripten_fetch_t* f) {
  FetchResponse r;
  r.status = f->status;
  if (r.status == 0) {
    r.error = f->readyState == 4 ? "network error, refused connection or timeout" : "request aborted";
  }
  const auto id = idOf(f);
  emscripten_fetch_close(f);
  if (gFetcher != nullptr) gFetcher->complete(id, std::move(r));
}

}  // namespace

BrowserFetcher::~BrowserFetcher() {
  if (gFetcher == this) gFetcher = nullptr;
}

Fetcher::RequestId BrowserFetcher::fetch(const std::string& url, Done done, std::uint32_t timeoutMs) {
  gFetcher = this;
  const RequestId id = nextId_++;
  pending_.emplace(id, std::move(done));
  emscripten_fetch_attr_t attr;
  emscripten_fetch_attr_init(&attr);
  std::strcpy(attr.requestMethod, "GET");
  attr.attributes = EMSCRIPTEN_FETCH_LOAD_TO_MEMORY;
  attr.onsuccess = onSuccess;
  attr.onerror = onError;
  attr.timeoutMSecs = timeoutMs;
  attr.userData = reinterpret_cast<void*>(static_cast<std::uintptr_t>(id));
  emscripten_fetch(&attr, url.c_str());
  return id;
}

void BrowserFetcher::cancel(RequestId id) {
  pending_.erase(id);
}

void BrowserFetcher::complete(RequestId id, FetchResponse response) {
  completed_.emplace_back(id, std::move(response));
}

void BrowserFetcher::poll() {
  std::vector<std::pair<RequestId, FetchResponse>> ready;
  ready.swap(completed_);
  for (auto& [id, response] : ready) {
    const auto it = pending_.find(id);
    if (it == pending_.end()) continue;  // cancelled
    Done done = std::move(it->second);
    pending_.erase(it);
    done(std::move(response));
  }
}

}  // namespace qv
