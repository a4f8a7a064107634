#include "qv/prep/Files.h"

#include <fcntl.h>
#include <sched.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zstd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <memory>
#include <thread>

#include "qv/core/Crc32.h"

namespace qv::prep {
namespace fs = std::filesystem;

namespace {

std::atomic<bool> gInterrupted{false};

extern "C" void onSignal(int) {
  gInterrupted.store(true);
}

std::string systemError(int error) {
  return std::strerror(error);
}

Status writeAll(int fd, const std::uint8_t* data, std::size_t size, const std::string& path) {
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::write(fd, data + done, size - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return Error{"cannot write " + path + ": " + systemError(errno)};
    }
    done += static_cast<std::size_t>(n);
  }
  return {};
}

}  // namespace

Result<std::vector<std::uint8_t>> readFile(const std::string& path, std::uint64_t maxBytes) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return Error{"cannot read " + path + ": " + systemError(errno)};
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    return Error{"cannot read " + path + ": not a regular file"};
  }
  if (static_cast<std::uint64_t>(st.st_size) > maxBytes) {
    ::close(fd);
    return Error{"cannot read " + path + ": " + std::to_string(st.st_size) + " bytes is more than the limit"};
  }
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(st.st_size));
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::read(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int e = errno;
      ::close(fd);
      return Error{"cannot read " + path + ": " + (n == 0 ? std::string("file shrank while reading") : systemError(e))};
    }
    done += static_cast<std::size_t>(n);
  }
  ::close(fd);
  return bytes;
}

Result<std::string> readTextFile(const std::string& path, std::uint64_t maxBytes) {
  auto bytes = readFile(path, maxBytes);
  if (!bytes.ok()) return Error{bytes.error()};
  return std::string(bytes->begin(), bytes->end());
}

Status writeFileAtomic(const std::string& path, std::span<const std::uint8_t> bytes) {
  const std::string temporary = path + ".tmp-" + std::to_string(::getpid());
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return Error{"cannot create " + temporary + ": " + systemError(errno)};
  Status written = writeAll(fd, bytes.data(), bytes.size(), path);
  if (written.ok() && ::fsync(fd) != 0) written = Error{"cannot write " + path + ": " + systemError(errno)};
  if (::close(fd) != 0 && written.ok()) written = Error{"cannot write " + path + ": " + systemError(errno)};
  if (!written.ok()) {
    ::unlink(temporary.c_str());
    return written;
  }
  if (::rename(temporary.c_str(), path.c_str()) != 0) {
    const int e = errno;
    ::unlink(temporary.c_str());
    return Error{"cannot replace " + path + ": " + systemError(e)};
  }
  return {};
}

Status writeFileAtomic(const std::string& path, const std::string& text) {
  return writeFileAtomic(path, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

Status writeStagedFile(const std::string& path, std::span<const std::uint8_t> bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return Error{"cannot create " + path + ": " + systemError(errno)};
  Status written = writeAll(fd, bytes.data(), bytes.size(), path);
  if (::close(fd) != 0 && written.ok()) written = Error{"cannot write " + path + ": " + systemError(errno)};
  return written;
}

Status writeStagedFile(const std::string& path, const std::string& text) {
  return writeStagedFile(path, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

Result<std::vector<std::uint8_t>> compressStoredFile(std::span<const std::uint8_t> bytes, int level) {
  const std::unique_ptr<ZSTD_CCtx, decltype(&ZSTD_freeCCtx)> cctx(ZSTD_createCCtx(), &ZSTD_freeCCtx);
  if (!cctx) return Error{"cannot compress: out of memory"};
  ZSTD_CCtx_setParameter(cctx.get(), ZSTD_c_compressionLevel, level);
  ZSTD_CCtx_setParameter(cctx.get(), ZSTD_c_checksumFlag, 1);
  ZSTD_CCtx_setParameter(cctx.get(), ZSTD_c_contentSizeFlag, 1);
  std::vector<std::uint8_t> out(ZSTD_compressBound(bytes.size()));
  const std::size_t n = ZSTD_compress2(cctx.get(), out.data(), out.size(), bytes.data(), bytes.size());
  if (ZSTD_isError(n)) return Error{std::string("cannot compress: ") + ZSTD_getErrorName(n)};
  out.resize(n);
  out.shrink_to_fit();
  return out;
}

Status makeDirectories(const std::string& path) {
  std::error_code ec;
  fs::create_directories(path, ec);
  if (ec) return Error{"cannot create directory " + path + ": " + ec.message()};
  return {};
}

Status linkOrCopyFile(const std::string& from, const std::string& to) {
  ::unlink(to.c_str());
  if (::link(from.c_str(), to.c_str()) == 0) return {};
  const int linkError = errno;
  if (linkError != EXDEV && linkError != EPERM && linkError != EMLINK && linkError != ENOTSUP) {
    return Error{to + ": cannot link it to " + from + " (" + std::strerror(linkError) + ")"};
  }
  auto bytes = readFile(from);
  if (!bytes.ok()) return Error{bytes.error()};
  return writeFileAtomic(to, *bytes);
}

void removeTree(const std::string& path) {
  std::error_code ec;
  fs::remove_all(path, ec);
}

Result<StagingDirectory> StagingDirectory::create(const std::string& target) {
  if (target.empty()) return Error{"no output directory given"};
  std::error_code ec;
  const fs::path t(target);
  if (fs::exists(t, ec)) {
    if (!fs::is_directory(t, ec)) return Error{target + " exists and is not a directory"};
    const bool isCity = fs::exists(t / "tileset.json", ec);
    const bool empty = fs::is_empty(t, ec);
    if (!isCity && !empty) {
      return Error{target + " exists and is not a QuakeView city directory; remove it or choose another --out"};
    }
  }
  const fs::path parent = t.has_parent_path() ? t.parent_path() : fs::path(".");
  if (!parent.empty()) {
    fs::create_directories(parent, ec);
    if (ec) return Error{"cannot create directory " + parent.string() + ": " + ec.message()};
  }
  std::string staging = target;
  while (!staging.empty() && staging.back() == '/') staging.pop_back();
  staging += ".tmp-" + std::to_string(::getpid());
  fs::remove_all(staging, ec);
  if (!fs::create_directory(staging, ec) || ec) {
    return Error{"cannot create directory " + staging + ": " + (ec ? ec.message() : std::string("exists"))};
  }
  return StagingDirectory(target, staging);
}

StagingDirectory::StagingDirectory(StagingDirectory&& other) noexcept
    : target_(std::move(other.target_)), staging_(std::move(other.staging_)), committed_(other.committed_) {
  other.committed_ = true;  // the moved-from object must not delete anything
}

StagingDirectory::~StagingDirectory() {
  if (!committed_) removeTree(staging_);
}

Status StagingDirectory::commit() {
  if (committed_) return Error{"staging directory committed twice"};
  // One sync of the file system holding the staged files (instead of one fsync per file): a late
  // write error (full disk, I/O error) surfaces here, before the previous city is replaced.
  {
    const int fd = ::open(staging_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return Error{"cannot open " + staging_ + ": " + systemError(errno)};
    const int synced = ::syncfs(fd);
    const int e = errno;
    ::close(fd);
    if (synced != 0) return Error{"cannot write the files of " + target_ + ": " + systemError(e)};
  }
  std::error_code ec;
  std::string target = target_;
  while (target.size() > 1 && target.back() == '/') target.pop_back();
  const std::string old = target + ".old-" + std::to_string(::getpid());
  const bool hadTarget = fs::exists(target, ec);
  if (hadTarget && ::rename(target.c_str(), old.c_str()) != 0) {
    return Error{"cannot move the previous " + target + " aside: " + systemError(errno)};
  }
  if (::rename(staging_.c_str(), target.c_str()) != 0) {
    const int e = errno;
    if (hadTarget) ::rename(old.c_str(), target.c_str());  // put the previous city back
    return Error{"cannot move the new city into " + target + ": " + systemError(e)};
  }
  committed_ = true;
  if (hadTarget) removeTree(old);
  return {};
}

void installInterruptHandler() {
  struct sigaction action {};
  action.sa_handler = onSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool interrupted() {
  return gInterrupted.load();
}

unsigned usableCores() {
  // The cores this process may run on (a batch job's CPU set: Slurm's task affinity, taskset,
  // a container's cpuset), not the machine's.
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0) return static_cast<unsigned>(CPU_COUNT(&set));
  return std::max(1u, std::thread::hardware_concurrency());
}

void parallelFor(std::size_t count, unsigned threads, const std::function<void(std::size_t)>& body) {
  const unsigned n = threads > 0 ? threads : usableCores();
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i = next++; i < count; i = next++) {
      if (interrupted()) return;
      body(i);
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < n && t < count; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
}

Result<FileDigest> fileDigest(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return Error{"cannot read " + path + ": " + systemError(errno)};
  std::vector<std::uint8_t> buffer(std::size_t{1} << 20);
  FileDigest digest;
  for (;;) {
    const ssize_t got = ::read(fd, buffer.data(), buffer.size());
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      const int error = errno;
      ::close(fd);
      return Error{"cannot read " + path + ": " + systemError(error)};
    }
    if (got == 0) break;
    digest.crc32 = qv::crc32(std::span<const std::uint8_t>(buffer.data(), static_cast<std::size_t>(got)), digest.crc32);
    digest.bytes += static_cast<std::uint64_t>(got);
  }
  ::close(fd);
  return digest;
}

}  // namespace qv::prep
