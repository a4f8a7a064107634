// File operations of quakeview-prep that never leave half-written output:
//   - writeFileAtomic writes a sibling temporary file, syncs it and renames it over the target;
//   - StagingDirectory builds a whole new output directory beside the target and swaps it into
//     place on commit(), so a failed or interrupted run leaves the previous directory intact;
//   - Ctrl-C (SIGINT/SIGTERM) sets a flag long loops poll, so they stop and clean up.
// Every failure is returned as a message naming the path and the system's reason (e.g. "No space
// left on device").
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "qv/core/Result.h"

namespace qv::prep {

Result<std::vector<std::uint8_t>> readFile(const std::string& path, std::uint64_t maxBytes = 8ull << 30);
Result<std::string> readTextFile(const std::string& path, std::uint64_t maxBytes = 4ull << 30);

/// Writes `bytes` to `path` through a temporary file in the same directory and a rename.
Status writeFileAtomic(const std::string& path, std::span<const std::uint8_t> bytes);
Status writeFileAtomic(const std::string& path, const std::string& text);

/// Writes a new file inside a StagingDirectory: no temporary and no sync of its own (the staging
/// directory is swapped in whole, and commit() syncs the file system once for all its files).
Status writeStagedFile(const std::string& path, std::span<const std::uint8_t> bytes);
Status writeStagedFile(const std::string& path, const std::string& text);

/// Zstandard level of the files the tools compress (response tiles): fast to write, and on the
/// 100,000-building synth-city a quarter to a half of the raw size (docs/formats.md).
inline constexpr int kStoredFileLevel = 6;

/// `bytes` as one Zstandard frame that declares its content size and carries zstd's checksum (the
/// stored form qv::unpackStoredFile reads; docs/formats.md "Compressed files").
Result<std::vector<std::uint8_t>> compressStoredFile(std::span<const std::uint8_t> bytes, int level = kStoredFileLevel);

/// Creates directories as needed (like mkdir -p).
Status makeDirectories(const std::string& path);

class StagingDirectory {
 public:
  /// Prepares `<target>.tmp-<pid>` beside `target`. Fails when `target` exists and is neither a
  /// directory holding tileset.json nor empty (we never delete what we did not write).
  static Result<StagingDirectory> create(const std::string& target);
  StagingDirectory(StagingDirectory&& other) noexcept;
  StagingDirectory& operator=(StagingDirectory&&) = delete;
  StagingDirectory(const StagingDirectory&) = delete;
  ~StagingDirectory();  ///< removes the staging directory unless committed

  [[nodiscard]] const std::string& path() const { return staging_; }
  /// Syncs the staged files to disk (once, for all of them), then moves the staging directory to
  /// the target, replacing a previous city there.
  Status commit();

 private:
  StagingDirectory(std::string target, std::string staging)
      : target_(std::move(target)), staging_(std::move(staging)) {}
  std::string target_;
  std::string staging_;
  bool committed_ = false;
};

/// Gives `to` the bytes of `from`: a hard link (no copy) where the file system allows it, else a
/// copy written atomically. A file already at `to` is replaced.
Status linkOrCopyFile(const std::string& from, const std::string& to);

/// Removes a directory tree; quiet when it does not exist.
void removeTree(const std::string& path);

/// Installs SIGINT/SIGTERM handlers that set the interrupted() flag (once per process).
void installInterruptHandler();
/// True after Ctrl-C: long loops stop, clean up and exit with a message.
bool interrupted();

/// The cores this process may run on: its CPU affinity (what a Slurm task, taskset or a container's
/// cpuset allows), else the machine's cores; at least 1.
unsigned usableCores();

/// Runs body(i) for every i in [0, count) on `threads` threads (0: usableCores()), this one included,
/// each taking the next index as it finishes one, and returns when all are done. After Ctrl-C
/// (interrupted()) no new index is started. `body` must be safe to run concurrently with itself.
void parallelFor(std::size_t count, unsigned threads, const std::function<void(std::size_t)>& body);

/// A file's size and CRC-32 (qv::crc32, as zlib's).
struct FileDigest {
  std::uint64_t bytes = 0;
  std::uint32_t crc32 = 0;
};
/// Reads the file at `path` in pieces through a fixed 1 MiB buffer (memory stays flat however large
/// the file) and returns its size and CRC-32; the error names the path and the system's reason.
Result<FileDigest> fileDigest(const std::string& path);

}  // namespace qv::prep
