// fuzz_tileset: arbitrary text into parseTileset. A manifest that parses must describe a proper
// tree (indices in range, every node reached once, paths relative), a ground layer whose cells lie
// in its pyramid once each, and parse again, unchanged in shape, after tilesetToJson.
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "FuzzSupport.h"
#include "qv/format/Tileset.h"

namespace {

void checkTree(const qv::Tileset& t) {
  using qv::fuzz::check;
  check(!t.nodes.empty(), "a parsed tileset without a root");
  std::vector<int> seen(t.nodes.size(), 0);
  seen[0] = 1;
  for (const qv::TileNode& n : t.nodes) {
    check(n.children.size() <= 4, "more than 4 children");
    for (std::uint32_t c : n.children) {
      check(c < t.nodes.size(), "child index out of range");
      check(++seen[c] == 1, "a node is reached twice");
    }
    check(!n.file.empty() && n.file[0] != '/' && n.file.find("..") == std::string::npos, "tile path not relative");
  }
  for (int s : seen) check(s == 1, "a node is not reached from the root");
}

/// The ground layer's cells lie in its pyramid, each once, with relative paths.
void checkGround(const qv::GroundLayer& g) {
  using qv::fuzz::check;
  check(g.levels >= 1 && g.levels <= 24 && g.size > 0.0, "a ground pyramid out of range");
  std::set<std::tuple<unsigned, std::uint32_t, std::uint32_t>> cells;
  for (const qv::GroundNode& n : g.nodes) {
    check(n.level < g.levels && n.x < (1u << n.level) && n.y < (1u << n.level), "a ground cell outside the pyramid");
    check(cells.emplace(n.level, n.x, n.y).second, "a ground cell listed twice");
    check(!n.file.empty() && n.file[0] != '/' && n.file.find("..") == std::string::npos, "ground path not relative");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace qv;
  constexpr std::string_view kName = "https://example.org/city/tileset.json";
  const std::string_view json(reinterpret_cast<const char*>(data), size);
  const Result<Tileset> tileset = parseTileset(json, kName);
  fuzz::checkErrorNamesInput(tileset, kName);
  if (!tileset.ok()) return 0;
  checkTree(*tileset);
  if (tileset->ground) checkGround(*tileset->ground);
  const Result<Tileset> again = parseTileset(tilesetToJson(*tileset), kName);
  if (!again.ok()) fuzz::contractBroken("a parsed tileset does not parse after writing:", again.error());
  fuzz::check(again->nodes.size() == tileset->nodes.size(), "round trip changed the node count");
  for (std::size_t i = 0; i < tileset->nodes.size(); ++i) {
    const TileNode& a = tileset->nodes[i];
    const TileNode& b = again->nodes[i];
    fuzz::check(a.key() == b.key() && a.file == b.file && a.children == b.children && a.bytes == b.bytes &&
                    a.crc32 == b.crc32 && a.response.has_value() == b.response.has_value(),
                "round trip changed a tile");
  }
  fuzz::check(again->ground.has_value() == tileset->ground.has_value() &&
                  (!tileset->ground || (again->ground->nodes.size() == tileset->ground->nodes.size() &&
                                        again->ground->features == tileset->ground->features &&
                                        again->ground->skipped == tileset->ground->skipped &&
                                        again->ground->levels == tileset->ground->levels)),
              "round trip changed the ground layer");
  fuzz::check(again->buildings == tileset->buildings && again->search.has_value() == tileset->search.has_value() &&
                  again->response.has_value() == tileset->response.has_value(),
              "round trip changed the manifest");
  return 0;
}
