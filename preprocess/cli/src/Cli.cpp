#include "qv/prep/Cli.h"

#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace qv::prep {

std::optional<Args> Args::parse(const std::vector<std::string>& argv, const std::vector<Spec>& specs,
                                std::string& error) {
  Args args;
  auto findSpec = [&](std::string_view name) -> const Spec* {
    for (const Spec& s : specs) {
      if (s.name == name) return &s;
    }
    return nullptr;
  };
  for (std::size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a.rfind("--", 0) != 0 || a.size() == 2) {
      args.positional_.push_back(a);
      continue;
    }
    std::string name = a.substr(2);
    std::optional<std::string> inlineValue;
    if (const auto eq = name.find('='); eq != std::string::npos) {
      inlineValue = name.substr(eq + 1);
      name = name.substr(0, eq);
    }
    const Spec* spec = findSpec(name);
    if (spec == nullptr) {
      error = "unknown option --" + name;
      return std::nullopt;
    }
    auto& slot = args.values_[name];
    if (!spec->takesValue) {
      if (inlineValue) {
        error = "--" + name + " takes no value";
        return std::nullopt;
      }
      slot.emplace_back();
      continue;
    }
    if (inlineValue) {
      slot.push_back(*inlineValue);
      continue;
    }
    // Values may start with '-' (negative numbers) but not with "--".
    auto isValue = [&](std::size_t j) { return j < argv.size() && argv[j].rfind("--", 0) != 0; };
    if (!isValue(i + 1)) {
      error = "--" + name + " needs a value";
      return std::nullopt;
    }
    slot.push_back(argv[++i]);
    while (spec->repeatable && isValue(i + 1)) slot.push_back(argv[++i]);
  }
  return args;
}

bool Args::has(std::string_view name) const {
  return values_.find(name) != values_.end();
}

std::optional<std::string> Args::value(std::string_view name) const {
  const auto it = values_.find(name);
  if (it == values_.end() || it->second.empty()) return std::nullopt;
  return it->second.back();
}

const std::vector<std::string>& Args::values(std::string_view name) const {
  static const std::vector<std::string> kNone;
  const auto it = values_.find(name);
  return it == values_.end() ? kNone : it->second;
}

std::optional<double> parseDouble(std::string_view text) {
  // std::from_chars for doubles is missing from em++'s libc++; strtod on a bounded copy is
  // portable and never throws.
  if (text.empty() || text.size() > 64) return std::nullopt;
  const std::string copy(text);
  char* end = nullptr;
  const double v = std::strtod(copy.c_str(), &end);
  if (end != copy.c_str() + copy.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::optional<std::int64_t> parseInteger(std::string_view text) {
  std::int64_t v = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || ptr != text.data() + text.size() || text.empty()) return std::nullopt;
  return v;
}

std::optional<std::vector<double>> parseNumberList(std::string_view text, std::size_t count) {
  std::vector<double> out;
  std::size_t start = 0;
  while (true) {
    const auto comma = text.find(',', start);
    const auto piece = text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    const auto v = parseDouble(piece);
    if (!v) return std::nullopt;
    out.push_back(*v);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (out.size() != count) return std::nullopt;
  return out;
}

bool interactiveTerminal() {
  const char* ci = std::getenv("CI");
  if (ci != nullptr && *ci != '\0') return false;
  return isatty(STDERR_FILENO) == 1;
}

Progress::Progress(std::string label, std::uint64_t total)
    : label_(std::move(label)), total_(total), enabled_(interactiveTerminal()) {}

Progress::~Progress() {
  finish();
}

void Progress::update(std::uint64_t done) {
  if (!enabled_ || finished_ || total_ == 0) return;
  const auto permille = static_cast<int>(std::min<std::uint64_t>(1000, done * 1000 / total_));
  if (permille == lastPermille_) return;
  lastPermille_ = permille;
  constexpr int kWidth = 30;
  const int filled = permille * kWidth / 1000;
  std::fprintf(stderr, "\r%s [%.*s%*s] %5.1f%%", label_.c_str(), filled, "##############################",
               kWidth - filled, "", permille / 10.0);
  std::fflush(stderr);
}

void Progress::finish() {
  if (!enabled_ || finished_) return;
  finished_ = true;
  if (lastPermille_ >= 0) std::fprintf(stderr, "\r%*s\r", static_cast<int>(label_.size()) + 45, "");
  std::fflush(stderr);
}

}  // namespace qv::prep
