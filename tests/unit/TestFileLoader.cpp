#include <catch2/catch.hpp>

#include <cstdio>

#include "MiniCity.h"
#include "qv/scene/FileLoader.h"

using namespace qv;
using test::FakeFetcher;

namespace {

// A loader over a fake server and a fake clock, recording what it reports and withdraws.
struct LoaderRig {
  FakeFetcher fetcher;
  FakeClock clock;
  std::vector<LoadError> errors;
  std::vector<std::string> withdrawn;
  FileLoader loader{fetcher, clock, [this](const LoadError& e) { errors.push_back(e); }};
  LoaderRig() {
    loader.setResolvedSink([this](const std::string& key) { withdrawn.push_back(key); });
  }
  /// A file served at `url` with these bytes, described by the manifest as served.
  FileSpec serve(FileKind kind, const std::string& url, std::vector<std::uint8_t> bytes) {
    FileSpec spec{kind, url, bytes.size(), crc32(bytes), kind == FileKind::Tile ? "1/0/1" : ""};
    fetcher.files[url] = std::move(bytes);
    return spec;
  }
  /// Starts `load` if due and delivers what the server answers; true when it was started.
  bool attempt(FileLoad& load, const FileSpec& spec, FileLoader::Accept accept = nullptr) {
    if (!accept) accept = [](std::vector<std::uint8_t>&) { return Verdict::loaded(); };
    const bool started = loader.start(load, spec, std::move(accept));
    fetcher.poll();
    return started;
  }
};

}  // namespace

TEST_CASE("A failing file is reported once, retried with growing backoff and withdrawn by its URL when it loads",
          "[scene][loader]") {
  LoaderRig rig;
  const FileSpec spec = rig.serve(FileKind::SearchIndex, "city/search.qvi", {1, 2, 3});
  rig.fetcher.statusOverride[spec.url] = 503;
  FileLoad load;
  REQUIRE(rig.attempt(load, spec));
  CHECK(load.state == TileState::Failed);
  REQUIRE(rig.errors.size() == 1);
  CHECK(rig.errors[0].key == spec.url);
  CHECK(rig.errors[0].kind == FileKind::SearchIndex);
  CHECK(rig.errors[0].message == "Search index city/search.qvi failed: HTTP 503");

  // 1 s after the first failure, then 2 s: not before.
  rig.clock.advance(0.99);
  CHECK_FALSE(rig.attempt(load, spec));
  rig.clock.advance(0.02);
  CHECK(rig.attempt(load, spec));
  rig.clock.advance(1.5);
  CHECK_FALSE(rig.attempt(load, spec));
  rig.clock.advance(0.6);
  CHECK(rig.attempt(load, spec));
  CHECK(rig.fetcher.count(spec.url) == 3);
  CHECK(rig.errors.size() == 1);  // reported once
  CHECK(rig.withdrawn.empty());

  rig.fetcher.statusOverride.clear();
  rig.clock.advance(4.0);
  REQUIRE(rig.attempt(load, spec));
  CHECK(load.state == TileState::Loaded);
  CHECK(load.failures == 0);
  CHECK(rig.withdrawn == std::vector<std::string>{spec.url});
  CHECK_FALSE(rig.attempt(load, spec));  // loaded: not fetched again
}

TEST_CASE("A tile that is missing waits 30 s, one the server may recover waits 1 s", "[scene][loader]") {
  LoaderRig rig;
  const FileSpec tile = rig.serve(FileKind::Tile, "city/tiles/1/0/1.qvt", {9, 9});
  for (const auto& [status, waitSeconds] : std::vector<std::pair<int, double>>{{404, 30.0}, {503, 1.0}, {429, 1.0}}) {
    CAPTURE(status);
    rig.fetcher.statusOverride[tile.url] = status;
    FileLoad load;
    REQUIRE(rig.attempt(load, tile));
    CHECK(rig.errors.back().message == "Tile 1/0/1 failed: city/tiles/1/0/1.qvt: HTTP " + std::to_string(status));
    rig.clock.advance(waitSeconds - 0.01);
    CHECK_FALSE(rig.loader.due(load));
    rig.clock.advance(0.02);
    CHECK(rig.loader.due(load));
  }
  // A response summary retries every failed fetch after the short backoff, a 404 included (as the
  // scene always did).
  const FileSpec summary = rig.serve(FileKind::ResponseSummary, "city/response/1/0/1.qvs", {1});
  rig.fetcher.statusOverride[summary.url] = 404;
  FileLoad load;
  REQUIRE(rig.attempt(load, summary));
  CHECK(rig.errors.back().message == "Response summary city/response/1/0/1.qvs failed: HTTP 404");
  rig.clock.advance(1.01);
  CHECK(rig.loader.due(load));
}

TEST_CASE("Bytes unlike the manifest's, and bytes the caller rejects, fail with what is wrong", "[scene][loader]") {
  LoaderRig rig;
  FileSpec tile = rig.serve(FileKind::Tile, "city/tiles/1/0/1.qvt", {1, 2, 3, 4});
  tile.bytes = 5;  // the manifest expects another file: a truncated or stale copy is served
  FileLoad load;
  REQUIRE(rig.attempt(load, tile));
  REQUIRE(rig.errors.size() == 1);
  const std::string& message = rig.errors[0].message;
  CHECK(message.starts_with("Tile 1/0/1 failed: city/tiles/1/0/1.qvt: 4 bytes with CRC-32 "));
  char manifestCrc[16];
  std::snprintf(manifestCrc, sizeof manifestCrc, "%08x", tile.crc32);
  CHECK(
      message.ends_with(", the manifest says 5 bytes, " + std::string(manifestCrc) + " (truncated, corrupt or stale)"));
  rig.clock.advance(1.01);
  CHECK(rig.loader.due(load));  // may be a transient fault of a cache or proxy

  // Decoded later (a tile under the frame's budget) and found bad: permanent, named by its tile.
  const FileSpec good = rig.serve(FileKind::Tile, "city/tiles/1/1/1.qvt", {7});
  FileLoad later;
  REQUIRE(rig.attempt(later, good, [](std::vector<std::uint8_t>&) { return Verdict::later(); }));
  CHECK(later.state == TileState::Loading);
  rig.loader.fail(later, good, "city/tiles/1/1/1.qvt: bad magic", false);
  CHECK(later.state == TileState::Failed);
  CHECK(rig.errors.back().message == "Tile 1/0/1 failed: city/tiles/1/1/1.qvt: bad magic");
  CHECK(rig.errors.back().key == good.url);
  rig.clock.advance(29.0);
  CHECK_FALSE(rig.loader.due(later));

  // A summary's own decoding problem is shown as the decoder says it.
  const FileSpec summary = rig.serve(FileKind::ResponseSummary, "city/r.qvs", {5});
  FileLoad s;
  REQUIRE(rig.attempt(s, summary, [](std::vector<std::uint8_t>&) {
    return Verdict::rejected("city/r.qvs: building count differs from the city tile", false);
  }));
  CHECK(rig.errors.back().message == "city/r.qvs: building count differs from the city tile");
}

TEST_CASE("Requests in flight are counted against one limit, and time limits grow with size and failures",
          "[scene][loader]") {
  LoaderRig rig;
  rig.loader.options().maxRequestsInFlight = 2;
  const FileSpec a = rig.serve(FileKind::ResponseHistory, "a.qvh", {1});
  const FileSpec b = rig.serve(FileKind::ResponseHistory, "b.qvh", {2});
  FileLoad la, lb;
  auto accept = [](std::vector<std::uint8_t>&) { return Verdict::loaded(); };
  REQUIRE(rig.loader.start(la, a, accept));
  CHECK(rig.loader.hasRoom());
  REQUIRE(rig.loader.start(lb, b, accept));
  CHECK_FALSE(rig.loader.hasRoom());
  CHECK_FALSE(rig.loader.start(la, a, accept));  // already loading
  rig.loader.cancel(lb);
  CHECK(rig.loader.inFlight() == 1);
  rig.fetcher.poll();
  CHECK(rig.loader.inFlight() == 0);
  CHECK(la.state == TileState::Loaded);

  FileLoaderOptions options;
  options.requestTimeoutMs = 20000;
  options.slowestBytesPerSecond = 1000;
  CHECK(requestTimeoutMs(options, 5000, 0) == 25000);  // 20 s plus 5 s of transfer
  CHECK(requestTimeoutMs(options, 5000, 1) == 50000);
  CHECK(requestTimeoutMs(options, 5000, 3) == 200000);
  CHECK(requestTimeoutMs(options, 5000, 9) == 200000);           // at most 8x
  CHECK(requestTimeoutMs(options, 10'000'000, 0) == 1'800'000);  // at most 30 minutes
}
