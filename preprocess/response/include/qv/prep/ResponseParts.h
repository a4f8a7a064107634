// A city's response in parts, for machines that share the work (docs/cluster.md):
//   quakeview-prep response --city DIR <options> --shard K/N   (K = 1..N, any order, any machine)
//   quakeview-prep response --city DIR --merge
// Each part analyses the leaves assignParts gives it (whole tiles, balanced by buildings, the
// same for a given city and N) and writes them, with what the merge needs, into the city's staging
// area, DIR/staging/part-K-of-N/ (first as a temporary folder, renamed when complete: a part that
// failed or was killed leaves no part behind). The merge checks that every part is there, complete
// (every file's size and CRC) and from the same run (the same tool, city and options: the run
// identity each part records), then computes the totals over all buildings and publishes the
// response as a one-machine run does (the same code: ResponseFinish.h). The published files are
// byte-identical to those of `response` without --shard on the same city. Until the merge commits
// the manifest, the city's previous response stays published; a refused merge changes nothing.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "qv/core/Result.h"
#include "qv/format/Tileset.h"
#include "qv/prep/Consequences.h"
#include "qv/prep/ResponseRun.h"
#include "qv/seismic/Loss.h"

namespace qv::prep {

/// The city's staging area for parts, relative to the city directory.
inline constexpr std::string_view kStagingFolder = "staging";
/// At most this many parts (a Slurm array of 10,000 tasks is beyond any city's leaves anyway).
inline constexpr unsigned kMaxParts = 10000;

/// "K/N" with 1 <= K <= N <= kMaxParts; nullopt otherwise.
std::optional<ShardSpec> parseShardSpec(std::string_view text);
/// "part-K-of-N": the part's folder in the staging area.
std::string partFolderName(const ShardSpec& shard);

/// The city's leaves in `parts` parts: whole leaves, each to the part with the fewest buildings so
/// far, largest leaves first (ties by node index), so parts hold about the same work; every leaf in
/// exactly one part; the same for the same tileset and `parts`. Each part's leaves in node order.
std::vector<std::vector<std::uint32_t>> assignParts(const Tileset& tileset, unsigned parts);

/// What makes two parts one run: named values (the tool and its solver kernel, the city's manifest,
/// every option that changes a result, the input files by name and CRC-32), in a fixed order.
using RunIdentity = std::vector<std::pair<std::string, std::string>>;
Result<RunIdentity> runIdentity(const Tileset& tileset, const ResponseRunOptions& options, unsigned parts);

/// One analysed building's losses as a part records them for the merge's totals.
struct PartLoss {
  std::uint64_t key = 0;  ///< (leaf node << 32) | index in the leaf
  int district = -1;      ///< -1: none
  LossClass lossClass;
  seismic::BuildingLoss loss;
};
/// A part's results file (results.qvp): per leaf its full summary (every section, uncompressed
/// encodeResponseSummary), and the losses of its buildings. Stored as a Zstandard frame.
struct PartResults {
  std::vector<std::pair<std::uint32_t, std::vector<std::uint8_t>>> leafSummaries;  ///< node, summary bytes
  std::vector<PartLoss> losses;
};
std::vector<std::uint8_t> encodePartResults(const PartResults& results);
/// Errors name `name` and what was being read; never reads out of bounds.
Result<PartResults> decodePartResults(std::span<const std::uint8_t> bytes, std::string_view name);

/// `response --merge`: publishes the parts in the city's staging area as the city's response, or
/// says which part is missing, incomplete or from another run and changes nothing. On success the
/// staging area is removed.
/// `scenario`: merge the parts of that scenario of a catalogue (their staging folder is
/// staging/scenario-I; 0: not a catalogue's). `threads`: cores for checking and adopting the
/// parts' files (0: every core this process may run on); the result does not depend on it.
Result<ResponseRunReport> mergeCityResponse(const std::string& cityDir, std::size_t scenario = 0, unsigned threads = 0);
/// The staging folder of a run's parts, relative to the city: "staging" or "staging/scenario-I".
std::string stagingFolder(std::size_t scenario);

}  // namespace qv::prep
