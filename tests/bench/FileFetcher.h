// A Fetcher over the local file system: URLs are paths. Used by the engine benchmark natively and
// under node (NODERAWFS), where no browser or HTTP server exists.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "qv/scene/Fetcher.h"

namespace qv::bench {

class FileFetcher final : public Fetcher {
 public:
  std::uint64_t bytesRead = 0;

  RequestId fetch(const std::string& url, Done done, std::uint32_t) override {
    const RequestId id = next_++;
    queue_.push_back({id, url, std::move(done)});
    return id;
  }
  void cancel(RequestId id) override {
    for (auto& q : queue_) {
      if (q.id == id) q.done = nullptr;
    }
  }
  void poll() override {
    std::vector<Queued> now;
    now.swap(queue_);
    for (Queued& q : now) {
      if (!q.done) continue;
      FetchResponse r;
      if (std::FILE* f = std::fopen(q.url.c_str(), "rb")) {
        std::fseek(f, 0, SEEK_END);
        const long size = std::ftell(f);
        std::fseek(f, 0, SEEK_SET);
        r.bytes.resize(static_cast<std::size_t>(size > 0 ? size : 0));
        const std::size_t got = std::fread(r.bytes.data(), 1, r.bytes.size(), f);
        std::fclose(f);
        r.status = got == r.bytes.size() ? 200 : 500;
        bytesRead += got;
      } else {
        r.status = 404;
      }
      q.done(std::move(r));
    }
  }

 private:
  struct Queued {
    RequestId id;
    std::string url;
    Done done;
  };
  std::vector<Queued> queue_;
  RequestId next_ = 1;
};

}  // namespace qv::bench
