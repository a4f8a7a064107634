// Stored files as Zstandard frames (docs/formats.md "Compressed files"): the decoders read
// a frame of a file as the file itself, and refuse damaged or hostile frames with a message that
// names the file. Frames are made here with Debian's libzstd, as quakeview-prep makes them.
#include <zstd.h>

#include <catch2/catch.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "qv/format/CityTile.h"
#include "qv/format/ResponseTile.h"
#include "qv/format/SearchIndex.h"
#include "qv/format/StoredFile.h"

using namespace qv;

namespace {

std::vector<std::uint8_t> frameOf(const std::vector<std::uint8_t>& bytes, bool declareSize = true) {
  ZSTD_CCtx* cctx = ZSTD_createCCtx();
  ZSTD_CCtx_setParameter(cctx, ZSTD_c_compressionLevel, 6);
  ZSTD_CCtx_setParameter(cctx, ZSTD_c_checksumFlag, 1);
  std::vector<std::uint8_t> out(ZSTD_compressBound(bytes.size()) + 64);
  std::size_t n = 0;
  if (declareSize) {
    n = ZSTD_compress2(cctx, out.data(), out.size(), bytes.data(), bytes.size());
  } else {
    // A streamed frame: zstd does not know the size when the frame starts.
    ZSTD_outBuffer o{out.data(), out.size(), 0};
    ZSTD_inBuffer i{bytes.data(), bytes.size(), 0};
    ZSTD_compressStream2(cctx, &o, &i, ZSTD_e_continue);
    while (ZSTD_compressStream2(cctx, &o, &i, ZSTD_e_end) != 0) {
    }
    n = o.pos;
  }
  ZSTD_freeCCtx(cctx);
  REQUIRE_FALSE(ZSTD_isError(n));
  out.resize(n);
  return out;
}

ResponseSummaryTile summaryOf(std::size_t buildings) {
  ResponseSummaryTile t;
  for (std::size_t b = 0; b < buildings; ++b) {
    BuildingResponse r;
    r.damage = b % 3 == 0 ? DamageState::Slight : DamageState::None;
    r.source = ResponseSource::Model;
    r.storeys = 2;
    r.peakDriftRatio = 0.001f * static_cast<float>(b % 17);
    r.firstStorey = static_cast<std::uint32_t>(2 * b);
    t.buildings.push_back(r);
    t.storeyPeakDrift.push_back(r.peakDriftRatio);
    t.storeyPeakDrift.push_back(r.peakDriftRatio * 0.5f);
  }
  return t;
}

}  // namespace

TEST_CASE("A response summary or history stored as a Zstandard frame reads as the file itself", "[format][stored]") {
  const ResponseSummaryTile summary = summaryOf(500);
  const std::vector<std::uint8_t> raw = encodeResponseSummary(summary);
  const std::vector<std::uint8_t> frame = frameOf(raw);
  REQUIRE(isCompressedFile(frame));
  CHECK_FALSE(isCompressedFile(raw));
  CHECK(frame.size() < raw.size() / 2);
  const auto fromFrame = decodeResponseSummary(frame, "0-0-0.qvs");
  REQUIRE(fromFrame.ok());
  const auto fromRaw = decodeResponseSummary(raw, "0-0-0.qvs");
  REQUIRE(fromRaw.ok());
  CHECK(fromFrame->buildings.size() == 500);
  CHECK(fromFrame->buildings[3].damage == DamageState::Slight);
  CHECK(fromFrame->storeyPeakDrift == fromRaw->storeyPeakDrift);
  CHECK(encodeResponseSummary(*fromFrame) == raw);

  ResponseHistoryTile history;
  history.durationSeconds = 4.0f;
  BuildingHistory h;
  h.floors = 2;
  h.bits = 8;
  h.sampleRateHz = 10.0f;
  h.sampleCount = 3;
  h.x.modes = 1;
  h.x.shapes = {0.5f, 1.0f};
  h.x.scales = {0.25f};
  h.x.coordinates = {1, -2, 127};
  history.buildings.assign(40, h);
  const std::vector<std::uint8_t> historyRaw = encodeResponseHistory(history);
  const auto historyBack = decodeResponseHistory(frameOf(historyRaw), "0-0-0.qvh");
  REQUIRE(historyBack.ok());
  CHECK(encodeResponseHistory(*historyBack) == historyRaw);

  const auto unpacked = unpackStoredFile(frameOf(raw), "x");
  REQUIRE(unpacked.ok());
  CHECK(*unpacked == raw);
  const auto plain = unpackStoredFile(raw, "x");
  REQUIRE(plain.ok());
  CHECK(*plain == raw);
}

TEST_CASE("A damaged, truncated, unsized or hostile frame is refused with the file named", "[format][stored]") {
  const std::vector<std::uint8_t> raw = encodeResponseSummary(summaryOf(300));
  const std::vector<std::uint8_t> frame = frameOf(raw);
  auto refused = [](const std::vector<std::uint8_t>& bytes, const std::string& expected) {
    const auto decoded = decodeResponseSummary(bytes, "response-1/2-1-3.qvs");
    REQUIRE_FALSE(decoded.ok());
    INFO(decoded.error());
    CHECK(decoded.error().find("response-1/2-1-3.qvs: compressed file (Zstandard frame): ") == 0);
    CHECK(decoded.error().find(expected) != std::string::npos);
  };
  SECTION("truncated") {
    refused(std::vector<std::uint8_t>(frame.begin(), frame.begin() + static_cast<std::ptrdiff_t>(frame.size() / 2)),
            "damaged or truncated");
    refused(std::vector<std::uint8_t>(frame.begin(), frame.begin() + 5), "damaged or truncated");
  }
  SECTION("a byte changed inside the compressed data (zstd's checksum, or the file's own CRC)") {
    std::vector<std::uint8_t> bad = frame;
    bad[bad.size() - 2] ^= 0x5A;  // inside the checksum: the content no longer matches it
    const auto decoded = decodeResponseSummary(bad, "response-1/2-1-3.qvs");
    REQUIRE_FALSE(decoded.ok());
    CHECK(decoded.error().find("response-1/2-1-3.qvs: ") == 0);
  }
  SECTION("bytes after the frame") {
    std::vector<std::uint8_t> bad = frame;
    bad.insert(bad.end(), {1, 2, 3});
    refused(bad, "3 bytes follow the frame's end");
  }
  SECTION("a frame that does not declare its size") {
    refused(frameOf(raw, false), "does not declare its content size");
  }
  SECTION("a few bytes that would expand to far more than any file of the city") {
    const std::vector<std::uint8_t> zeros(64u << 20, 0);
    const std::vector<std::uint8_t> bomb = frameOf(zeros);
    REQUIRE(bomb.size() * kMaxStoredFileRatio < zeros.size());
    refused(bomb, "over the limit");
  }
}

TEST_CASE("City tiles and the search index stored as Zstandard frames read as the files themselves",
          "[format][stored]") {
  std::vector<SearchEntry> entries;
  for (int i = 0; i < 50; ++i) {
    SearchEntry e;
    e.id = "w" + std::to_string(1000 + i);
    e.name = i % 2 == 0 ? "Tower " + std::to_string(i) : "";
    e.use = "office";
    e.x = static_cast<float>(i);
    entries.push_back(e);
  }
  const std::vector<std::uint8_t> index = encodeSearchIndex(entries);
  const auto fromFrame = decodeSearchIndex(frameOf(index), "search.qvi");
  REQUIRE(fromFrame.ok());
  REQUIRE(fromFrame->size() == 50);
  CHECK((*fromFrame)[4].name == "Tower 4");
  CHECK(encodeSearchIndex(*fromFrame) == index);

  CityTile tile;
  tile.originX = 100.0;
  tile.extent = 50.0f;
  const std::vector<std::uint8_t> tileBytes = encodeCityTile(tile);
  const auto tileBack = decodeCityTile(frameOf(tileBytes), "tiles/0-0-0.qvt");
  REQUIRE(tileBack.ok());
  CHECK(encodeCityTile(*tileBack) == tileBytes);

  std::vector<std::uint8_t> truncated = frameOf(tileBytes);
  truncated.resize(truncated.size() - 3);
  const auto bad = decodeCityTile(truncated, "tiles/0-0-0.qvt");
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().find("tiles/0-0-0.qvt: compressed file (Zstandard frame): ") == 0);
}
