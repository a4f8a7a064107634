// Command-line conventions of quakeview-prep: argument parsing, exit codes, messages, progress.
//
// Exit codes: 0 success; 1 the data was bad or a file could not be read or written (the message
// names the file and the position); 2 the command line was wrong (the message says how to fix it).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace qv::prep {

enum ExitCode : int { kExitOk = 0, kExitDataError = 1, kExitUsage = 2 };

/// Parsed "--flag value", "--flag=value", "--switch" and positional arguments. A flag declared
/// repeatable collects every value ("--input A B C" or "--input A --input B").
class Args {
 public:
  struct Spec {
    std::string name;  ///< without dashes: "input"
    bool takesValue = true;
    bool repeatable = false;  ///< values until the next "--": "--input a.osm b.pbf"
  };

  /// Parses argv after the command name. On a usage error returns nullopt and sets `error`.
  static std::optional<Args> parse(const std::vector<std::string>& argv, const std::vector<Spec>& specs,
                                   std::string& error);

  [[nodiscard]] bool has(std::string_view name) const;
  /// The last value of a flag, or nullopt.
  [[nodiscard]] std::optional<std::string> value(std::string_view name) const;
  [[nodiscard]] const std::vector<std::string>& values(std::string_view name) const;
  [[nodiscard]] const std::vector<std::string>& positional() const { return positional_; }

 private:
  std::map<std::string, std::vector<std::string>, std::less<>> values_;
  std::vector<std::string> positional_;
};

/// Strict number parsing (whole string, finite): "30", "-74.0", "1e3". No exceptions.
std::optional<double> parseDouble(std::string_view text);
std::optional<std::int64_t> parseInteger(std::string_view text);
/// "LON,LAT" or "A,B,C": exactly `count` comma-separated finite numbers.
std::optional<std::vector<double>> parseNumberList(std::string_view text, std::size_t count);

/// A progress bar on a terminal (stderr is a TTY and CI is not set); silent otherwise.
class Progress {
 public:
  Progress(std::string label, std::uint64_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  void update(std::uint64_t done);
  void finish();

 private:
  std::string label_;
  std::uint64_t total_;
  bool enabled_;
  int lastPermille_ = -1;
  bool finished_ = false;
};

/// True when long runs may draw progress bars (stderr is a terminal, not CI).
bool interactiveTerminal();

}  // namespace qv::prep
