#include "qv/options/AppOptions.h"

#include <array>
#include <cmath>
#include <cstdlib>

#include "qv/core/Text.h"

namespace qv {
namespace {

constexpr std::array<AppArgument, 18> kArguments = {{
    {"--data", ArgumentSource::UrlQuery, "data", true},
    {"--scene", ArgumentSource::UrlQuery, "scene", true},
    {"--no-antialias", ArgumentSource::UrlQuery, "aa", false},
    {"--antialias", ArgumentSource::UrlQuery, "aa", false},
    {"--quality", ArgumentSource::UrlQuery, "quality", true},
    {"--memory-mb", ArgumentSource::UrlQuery, "memory", true},
    {"--bench", ArgumentSource::UrlQuery, "bench", true},
    {"--camera", ArgumentSource::UrlHash, "cam", true},
    {"--time", ArgumentSource::UrlHash, "t", true},
    {"--playing", ArgumentSource::UrlHash, "play", true},
    {"--select", ArgumentSource::UrlHash, "sel", true},
    {"--filters", ArgumentSource::UrlHash, "f", true},
    {"--page-origin", ArgumentSource::Shell, "", true},
    {"--data-origin", ArgumentSource::Shell, "", true},
    {"--allow-origin", ArgumentSource::Shell, "", true},
    {"--shell-error", ArgumentSource::Shell, "", true},
    {"--webgl-renderer", ArgumentSource::Shell, "", true},
    {"--map2d", ArgumentSource::Shell, "", false},
}};

const AppArgument* findArgument(std::string_view argument) {
  for (const AppArgument& a : kArguments) {
    if (a.argument == argument) return &a;
  }
  return nullptr;
}

// A value from the URL as it may appear inside a message: display-safe, at most about 60 bytes.
std::string shown(std::string_view value) {
  constexpr std::size_t kLimit = 60;
  if (value.size() <= kLimit) return displaySafe(value);
  std::size_t cut = kLimit;
  while (cut > 0 && (static_cast<unsigned char>(value[cut]) & 0xC0u) == 0x80u) --cut;  // a whole UTF-8 character
  return displaySafe(value.substr(0, cut)) + "…";
}

// "name=value" of the URL parameter behind an argument, for messages.
std::string named(const AppArgument& a, std::string_view value) {
  return std::string(a.urlName) + "=" + shown(value);
}

// A whole-string finite number (strtod's syntax), or nullopt.
std::optional<double> parseNumber(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double number = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(number)) return std::nullopt;
  return number;
}

std::vector<std::string_view> splitCommas(std::string_view text) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    parts.push_back(text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) return parts;
    start = comma + 1;
  }
}

// x,y,distance,headingDeg,pitchDeg[,fovDeg], each field a number within CameraLimits.
Result<CameraState> parseCamera(std::string_view text) {
  const std::vector<std::string_view> parts = splitCommas(text);
  if (parts.size() != 5 && parts.size() != 6) {
    return Error{std::to_string(parts.size()) + " values where 5 or 6 are expected (x,y,distance,heading,pitch[,fov])"};
  }
  static const char* const kFields[6] = {"x", "y", "distance", "heading", "pitch", "fov"};
  std::array<double, 6> v{0.0, 0.0, 0.0, 0.0, 0.0, 45.0};
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const std::optional<double> number = parseNumber(std::string(parts[k]));
    if (!number) return Error{std::string(kFields[k]) + " '" + shown(parts[k]) + "' is not a number"};
    v[k] = *number;
  }
  const CameraState given{v[0], v[1], v[2], v[3], v[4], v[5]};
  CameraState checked = given;
  if (!sanitizeCamera(checked, given)) {
    const std::array<double, 6> c{checked.x,          checked.y,        checked.distance,
                                  checked.headingDeg, checked.pitchDeg, checked.fovDeg};
    // A heading of any size is wrapped into [0, 360), not refused.
    for (std::size_t k = 0; k < parts.size(); ++k) {
      if (k != 3 && c[k] != v[k]) {
        return Error{std::string(kFields[k]) + " " + shown(parts[k]) + " is outside the camera's limits"};
      }
    }
    return Error{"a value is outside the camera's limits"};
  }
  return checked;
}

// What one argument's value does to the options; `a` is its table entry.
void applyValue(const AppArgument& a, const std::string& v, AppOptions& options, std::vector<std::string>& errors) {
  const std::string_view name = a.argument;
  if (name == "--data") {
    options.dataUrl = v;
  } else if (name == "--scene") {
    options.scene = "test";
    if (v != "test")
      errors.push_back("The scene in the URL (" + named(a, v) +
                       ") is not known (known: test); showing the test scene.");
  } else if (name == "--quality") {
    if (v == "auto") {
      options.quality = QualityChoice::Auto;
    } else if (v == "high") {
      options.quality = QualityChoice::High;
    } else if (v == "balanced") {
      options.quality = QualityChoice::Balanced;
    } else if (v == "low") {
      options.quality = QualityChoice::Low;
    } else {
      errors.push_back("The quality in the URL (" + named(a, v) +
                       ") is not auto, high, balanced or low; the device decides.");
    }
  } else if (name == "--webgl-renderer") {
    options.webGlRenderer = displaySafe(v.substr(0, 200));
  } else if (name == "--memory-mb") {
    const std::optional<double> mb = parseNumber(v);
    if (!mb || !(*mb >= 16.0 && *mb <= 4096.0)) {
      errors.push_back("The memory budget in the URL (" + named(a, v) +
                       ") is not a number of megabytes from 16 to 4096; using " +
                       std::to_string(options.city.memoryBudgetBytes >> 20) + " MB.");
    } else {
      options.city.memoryBudgetBytes = static_cast<std::uint64_t>(*mb * 1048576.0);
    }
  } else if (name == "--bench") {
    const std::optional<double> seconds = parseNumber(v);
    if (!seconds || !(*seconds >= 1.0 && *seconds <= 3600.0)) {
      errors.push_back("The benchmark length in the URL (" + named(a, v) +
                       ") is not a number of seconds from 1 to 3600; no benchmark run.");
    } else {
      options.benchSeconds = *seconds;
    }
  } else if (name == "--camera") {
    Result<CameraState> camera = parseCamera(v);
    if (camera) {
      options.camera = *camera;
    } else {
      errors.push_back("The camera in the link (" + named(a, v) + ") is not valid: " + camera.error() +
                       "; showing the default view.");
    }
  } else if (name == "--time") {
    const std::optional<double> t = parseNumber(v);
    if (!t || *t < 0.0) {
      errors.push_back("The time in the link (" + named(a, v) +
                       ") is not a number of seconds from 0; starting at 0 s.");
    } else {
      options.timeSeconds = *t;
    }
  } else if (name == "--playing") {
    if (v == "0" || v == "1") {
      options.playing = v == "1";
    } else {
      errors.push_back("The play state in the link (" + named(a, v) + ") is not 0 or 1; playing.");
    }
  } else if (name == "--select") {
    if (v.empty() || v.size() > 200 || v.find_first_of("\n\r\t") != std::string::npos) {
      errors.push_back("The selected building in the link (" + named(a, v) +
                       ") is not a valid id (1 to 200 bytes, no tab or line break); nothing is selected.");
    } else {
      options.select = v;
    }
  } else if (name == "--filters") {
    Result<BuildingFilters> filters = parseFilters(v);
    if (filters) {
      options.filters = *filters;
    } else {
      options.filters.reset();
      errors.push_back("The filters in the link (" + named(a, v) + ") are not valid: " + filters.error() +
                       "; showing every building.");
    }
  } else if (name == "--page-origin") {
    options.city.origin.pageOrigin = v;
  } else if (name == "--data-origin") {
    options.city.origin.urlOrigin = v;
  } else if (name == "--allow-origin") {
    options.city.origin.allowedOrigins.push_back(v);
  } else if (name == "--shell-error") {
    errors.push_back(v);  // a message of the page shell (a broken config.json)
  }
}

}  // namespace

std::span<const AppArgument> appArguments() {
  return kArguments;
}

Result<BuildingFilters> parseFilters(std::string_view text) {
  if (text.size() > kMaxFilterTextBytes) {
    return Error{"longer than " + std::to_string(kMaxFilterTextBytes) + " characters"};
  }
  const std::vector<std::string_view> parts = splitCommas(text);
  if (parts.size() != 3 && parts.size() != 4) {
    return Error{std::to_string(parts.size()) + (parts.size() == 1 ? " field" : " fields") +
                 " where 3 or 4 are expected (minDamage,use,critical[,probability])"};
  }
  BuildingFilters f;
  if (!parts[0].empty()) {
    if (parts[0].size() != 1 || parts[0][0] < '0' || parts[0][0] > '4') {
      return Error{"minDamage '" + shown(parts[0]) + "' is not a damage state 0 to 4"};
    }
    f.minDamage = parts[0][0] - '0';
  }
  for (const char c : parts[1]) {
    if (!((c >= 'a' && c <= 'z') || c == '_' || c == '+')) {
      return Error{"use '" + shown(parts[1]) + "' has characters other than a to z, _ and +"};
    }
  }
  const std::string_view uses = parts[1];
  if (!uses.empty() && (uses.front() == '+' || uses.back() == '+' || uses.find("++") != std::string_view::npos)) {
    return Error{"use '" + shown(uses) + "' has an empty use between the '+' that join uses"};
  }
  f.use = std::string(uses);
  const std::string_view critical = parts[2];
  if (critical == "1") {
    f.criticalOnly = true;
  } else if (!critical.empty() && critical != "0") {
    std::string_view rest = critical;
    while (true) {
      const std::size_t plus = rest.find('+');
      const std::optional<FacilityCategory> category = parseFacilityCategory(rest.substr(0, plus));
      if (!category) {
        return Error{"critical '" + shown(critical) + "' is not 0, 1 or categories joined by '+' (" +
                     "essential, school_shelter, high_occupancy, hazardous)"};
      }
      f.categories |= facilityCategoryBit(*category);
      if (plus == std::string_view::npos) break;
      rest.remove_prefix(plus + 1);
    }
  }
  if (parts.size() == 4 && !parts[3].empty()) {
    // "state:percent": P(structural damage >= state) at least percent %, state 1..4, percent 1..100.
    const std::string_view p = parts[3];
    const std::size_t colon = p.find(':');
    const std::string_view state = p.substr(0, colon);
    const std::string_view percent = colon == std::string_view::npos ? std::string_view() : p.substr(colon + 1);
    int value = 0;
    bool digits = !percent.empty() && percent.size() <= 3;
    for (const char c : percent) {
      if (c < '0' || c > '9')
        digits = false;
      else
        value = value * 10 + (c - '0');
    }
    if (state.size() != 1 || state[0] < '1' || state[0] > '4' || !digits || value < 1 || value > 100) {
      return Error{"probability '" + shown(p) + "' is not state:percent with a damage state 1 to 4 and a percent " +
                   "1 to 100 (e.g. 2:10, P(at least moderate) at least 10 %)"};
    }
    f.probabilityState = state[0] - '0';
    f.minProbabilityPercent = value;
  }
  return f;
}

AppOptions parseAppOptions(const std::vector<std::string>& args, std::vector<std::string>& errors) {
  AppOptions options;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const AppArgument* a = findArgument(args[i]);
    if (a == nullptr) {
      errors.push_back("Ignored unknown engine argument '" + shown(args[i]) + "'.");
    } else if (a->argument == "--map2d") {
      options.map2d = true;
    } else if (!a->takesValue) {
      // The flags: --no-antialias (?aa=0) and --antialias (?aa=1); the later one wins.
      options.antialiasForced = a->argument == "--antialias";
      options.antialias = options.antialiasForced;
    } else if (i + 1 >= args.size()) {
      errors.push_back("Ignored engine argument '" + args[i] + "' without a value.");
    } else {
      applyValue(*a, args[++i], options, errors);
    }
  }
  if (options.scene == "test") options.dataUrl.clear();
  return options;
}

}  // namespace qv
