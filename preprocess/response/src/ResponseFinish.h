// The end of a response run, shared by the one-machine run (ResponseRun.cpp) and the merge of a
// sharded run's parts (ResponseParts.cpp), so both publish the same bytes: the consequence totals
// over every building in the city's order, the manifest's mean history rate in the leaves' order,
// consequences.json, then the writer's commit.
#pragma once

#include <cstdint>
#include <vector>

#include "qv/core/Result.h"
#include "qv/format/Tileset.h"
#include "qv/prep/Consequences.h"
#include "qv/prep/ResponseParts.h"
#include "qv/prep/ResponseRun.h"
#include "qv/prep/ResponseWriter.h"
#include "qv/seismic/Loss.h"

namespace qv::prep::detail {

/// Every analysed building's losses, in any order; key = (leaf node << 32) | index in the leaf.
struct RunLosses {
  std::vector<seismic::BuildingLoss> losses;
  std::vector<int> district;  ///< per building, -1: none; empty without districts
  std::vector<std::uint64_t> key;
  std::vector<LossClass> classes;
  void append(RunLosses&& other);
};

/// The histories' sample rates summed over a leaf's buildings (in the leaf's analysis order).
struct LeafRate {
  double sum = 0.0;
  std::uint64_t count = 0;
};

struct FinishInputs {
  ResponseInfo info;                ///< as the run describes it (the rest is filled here)
  RunLosses losses;                 ///< every building of the city with a result
  std::vector<LeafRate> leafRates;  ///< per tileset node (0 for inner nodes)
  const Districts* districts = nullptr;
  seismic::PopulationFigures population;
};

/// The records --motion names: each file as given, each folder's regular files (not hidden) by name.
Result<std::vector<std::string>> expandMotionPaths(const std::vector<std::string>& paths);

/// One part of a sharded run (`response --shard K/N`, ResponseParts.h): its leaves, its folder in
/// the staging area, and its publication there once every leaf is written.
class PartRun {
 public:
  static Result<PartRun> begin(const std::string& cityDir, const Tileset& tileset, const ResponseRunOptions& options,
                               ShardSpec shard);
  [[nodiscard]] const std::vector<std::uint32_t>& leaves() const { return leaves_; }
  /// The temporary folder the part is written into, relative to the city.
  [[nodiscard]] const std::string& folder() const { return folder_; }
  /// Writes the part's results, notes, description and manifest (part.json, last) into the folder
  /// and renames it to staging/part-K-of-N, replacing an earlier attempt of the same part.
  Status publish(ResponseWriter& writer, const FinishInputs& finish, const ResponseRunReport& report);

 private:
  std::string cityDir_, folder_;
  ShardSpec shard_;
  RunIdentity identity_;
  std::vector<std::uint32_t> leaves_;
  Tileset tileset_;
  std::string districtsPath_;
  std::size_t scenario_ = 0;
  std::vector<std::string> scenarioNames_;
};

/// Writes consequences.json and commits the writer's response; fills the report's totals, counts,
/// bytes and folder.
Status finishResponse(ResponseWriter& writer, FinishInputs in, ResponseRunReport& report);

}  // namespace qv::prep::detail
