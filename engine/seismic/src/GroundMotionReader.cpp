#include "qv/seismic/GroundMotionReader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "qv/core/NumberFormat.h"

namespace qv::seismic {
namespace {

constexpr std::size_t kMaxFileBytes = std::size_t{256} << 20;
// Limits checked before the per-line structures are allocated (a line costs about 100 bytes of
// bookkeeping, so a file of blank lines must not be read whole): 2 Mi samples is almost 6 hours at
// 100 Hz, far beyond any record; the line limit leaves room for a header and blank lines.
constexpr std::size_t kMaxSamples = std::size_t{1} << 21;
constexpr std::size_t kMaxLines = kMaxSamples + (std::size_t{1} << 16);

struct Line {
  std::size_t number = 0;  // 1-based
  std::string_view text;
};

Error errorAt(std::string_view name, std::size_t line, const std::string& message) {
  // Appended piece by piece (GCC 12 at -O3 warns falsely about "literal" + std::string).
  std::string text(name);
  if (line > 0) {
    text += ':';
    text += std::to_string(line);
  }
  text += ": ";
  text += message;
  return fail(std::move(text));
}

std::vector<Line> splitLines(std::string_view text) {
  std::vector<Line> lines;
  std::size_t start = 0;
  std::size_t number = 1;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back({number, line});
    if (end == text.size()) break;
    start = end + 1;
    ++number;
  }
  return lines;
}

bool isSeparator(char c) {
  return c == ' ' || c == '\t' || c == ',' || c == ';' || c == '\f' || c == '\v';
}

// At most maxTokens + 1 tokens (one more than allowed tells the caller the line has too many).
std::vector<std::string_view> tokenize(std::string_view line, std::size_t maxTokens) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size() && tokens.size() <= maxTokens) {
    while (i < line.size() && isSeparator(line[i])) ++i;
    const std::size_t begin = i;
    while (i < line.size() && !isSeparator(line[i])) ++i;
    if (i > begin) tokens.push_back(line.substr(begin, i - begin));
  }
  return tokens;
}

enum class NumberStatus { Ok, NotNumber, NotFinite };

// Strict parse of one token (whole token, strtod on a bounded copy; D exponents as E).
NumberStatus parseNumber(std::string_view token, double& out) {
  if (token.empty() || token.size() > 63) return NumberStatus::NotNumber;
  char buffer[64];
  for (std::size_t i = 0; i < token.size(); ++i) buffer[i] = token[i] == 'D' || token[i] == 'd' ? 'E' : token[i];
  buffer[token.size()] = '\0';
  // strtod accepts hexadecimal, "inf" and "nan"; the first is not a record value, the others are
  // reported as not finite.
  for (std::size_t i = 0; i < token.size(); ++i) {
    if (buffer[i] == 'x' || buffer[i] == 'X') return NumberStatus::NotNumber;
  }
  char* end = nullptr;
  const double v = std::strtod(buffer, &end);
  if (end != buffer + token.size()) return NumberStatus::NotNumber;
  if (!std::isfinite(v)) return NumberStatus::NotFinite;
  out = v;
  return NumberStatus::Ok;
}

// Fortran fixed-width fields can run together when a value fills its field: "0.123-0.456". Splits
// before each sign that follows a digit or a point (not an exponent letter).
bool parseRunTogether(std::string_view token, std::vector<double>& out) {
  std::vector<double> values;
  std::size_t begin = 0;
  for (std::size_t i = 1; i <= token.size(); ++i) {
    const bool split = i == token.size() || ((token[i] == '-' || token[i] == '+') &&
                                             (token[i - 1] == '.' || (token[i - 1] >= '0' && token[i - 1] <= '9')));
    if (!split) continue;
    double v = 0.0;
    if (parseNumber(token.substr(begin, i - begin), v) != NumberStatus::Ok) return false;
    values.push_back(v);
    begin = i;
  }
  if (values.size() < 2) return false;
  out.insert(out.end(), values.begin(), values.end());
  return true;
}

enum class LineKind { Blank, Numbers, Text };

struct ParsedLine {
  LineKind kind = LineKind::Blank;
  std::vector<double> values;
  std::string_view badToken;  // first token that is not a number (Text lines)
  bool badIsNotFinite = false;
  bool tooManyValues = false;  // more than kMaxSamples tokens (values not kept)
};

ParsedLine classify(std::string_view line) {
  ParsedLine parsed;
  const auto tokens = tokenize(line, kMaxSamples);
  if (tokens.empty()) return parsed;
  parsed.kind = LineKind::Numbers;
  if (tokens.size() > kMaxSamples) {
    parsed.tooManyValues = true;
    return parsed;
  }
  for (const std::string_view token : tokens) {
    double v = 0.0;
    const NumberStatus status = parseNumber(token, v);
    if (status == NumberStatus::Ok) {
      parsed.values.push_back(v);
      continue;
    }
    if (status == NumberStatus::NotNumber && parseRunTogether(token, parsed.values)) continue;
    parsed.kind = LineKind::Text;
    parsed.badToken = token;
    parsed.badIsNotFinite = status == NumberStatus::NotFinite;
    return parsed;
  }
  return parsed;
}

std::string upper(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  }
  return out;
}

// Words of a header line: upper case, split on anything but letters, digits, '.', '/', '^', '+', '-'.
std::vector<std::string> headerWords(std::string_view line) {
  const std::string u = upper(line);
  std::vector<std::string> words;
  std::string current;
  for (const char c : u) {
    const bool keep =
        (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '/' || c == '^' || c == '+' || c == '-';
    if (keep) {
      current += c;
    } else if (!current.empty()) {
      words.push_back(current);
      current.clear();
    }
  }
  if (!current.empty()) words.push_back(current);
  return words;
}

std::optional<double> wordNumber(const std::string& word) {
  double v = 0.0;
  if (parseNumber(word, v) != NumberStatus::Ok) return std::nullopt;
  return v;
}

struct HeaderInfo {
  std::optional<double> points;
  std::size_t pointsLine = 0;
  std::optional<double> timeStepS;
  std::size_t timeStepLine = 0;
  std::optional<AccelerationUnit> units;
  std::size_t unitsLine = 0;
};

// A unit as written in a header, upper case: trailing sentence punctuation ("UNITS OF G.") and the
// spelling of a power ("CM/SEC**2", "M/S^2", "M/S 2" once '*' split the word) do not matter.
// `next` is the following word of the line, which completes "M/S" + "2".
std::optional<AccelerationUnit> unitWord(std::string w, std::string_view next = {}) {
  w.erase(std::remove_if(w.begin(), w.end(), [](char c) { return c == '*' || c == '^' || c == ' '; }), w.end());
  while (!w.empty() && (w.back() == '.' || w.back() == ',' || w.back() == ';' || w.back() == ':')) w.pop_back();
  while (!w.empty() && w.front() == '.') w.erase(w.begin());
  if ((w == "M/S" || w == "M/SEC" || w == "CM/S" || w == "CM/SEC") && next == "2") w += '2';
  if (w == "G") return AccelerationUnit::G;
  if (w == "GAL" || w == "GALS" || w.rfind("CM/S", 0) == 0) return AccelerationUnit::CentimetresPerSecond2;
  if (w == "M/S/S" || w == "M/S2" || w == "M/SEC/SEC" || w == "M/SEC2" || w == "MPS2")
    return AccelerationUnit::MetresPerSecond2;
  return std::nullopt;
}

// A unit in brackets anywhere on the line: "ACCELERATION (g)", "[CM/SEC**2]".
std::optional<AccelerationUnit> bracketedUnit(const std::string& upperLine) {
  std::size_t open = upperLine.find_first_of("([");
  while (open != std::string::npos) {
    const std::size_t close = upperLine.find_first_of(")]", open + 1);
    if (close == std::string::npos) break;
    if (const auto u = unitWord(upperLine.substr(open + 1, close - open - 1))) return u;
    open = upperLine.find_first_of("([", close + 1);
  }
  return std::nullopt;
}

// Reads what a header line says about the count, step and units.
void scanHeaderLine(const Line& line, HeaderInfo& info) {
  const auto words = headerWords(line.text);
  bool mentionsUnits = false;
  for (const auto& w : words) {
    if (w.rfind("UNIT", 0) == 0 || w == "ACCELERATION" || w == "ACCEL" || w == "ACC") mentionsUnits = true;
  }
  if (!info.units) {
    if (const auto u = bracketedUnit(upper(line.text))) {
      info.units = u;
      info.unitsLine = line.number;
    }
  }
  for (std::size_t i = 0; i < words.size(); ++i) {
    const std::string& w = words[i];
    // "NPTS= 4096" / "DT= .01" (the '=' is a separator, so the value is the next word).
    if ((w == "NPTS" || w == "NPT" || w == "NPOINTS") && i + 1 < words.size()) {
      if (const auto v = wordNumber(words[i + 1])) {
        info.points = v;
        info.pointsLine = line.number;
      }
    }
    if (w == "DT" && i + 1 < words.size()) {
      if (const auto v = wordNumber(words[i + 1])) {
        info.timeStepS = v;
        info.timeStepLine = line.number;
      }
    }
    // Pre-NGA PEER: "3000  .0100  NPTS, DT".
    if (w == "NPTS" && i + 1 < words.size() && words[i + 1] == "DT" && i >= 2) {
      const auto n = wordNumber(words[i - 2]);
      const auto dt = wordNumber(words[i - 1]);
      if (n && dt) {
        info.points = n;
        info.pointsLine = line.number;
        info.timeStepS = dt;
        info.timeStepLine = line.number;
      }
    }
    // Prose: "1559 points at equal spacing of 0.02 sec".
    if ((w == "POINTS" || w == "PTS") && i >= 1 && !info.points) {
      if (const auto n = wordNumber(words[i - 1])) {
        info.points = n;
        info.pointsLine = line.number;
      }
    }
    if (w == "SPACING" && i + 2 < words.size() && words[i + 1] == "OF" && !info.timeStepS) {
      if (const auto dt = wordNumber(words[i + 2])) {
        info.timeStepS = dt;
        info.timeStepLine = line.number;
      }
    }
    // A unit word counts on a line about units or acceleration, or after "in" ("values in g").
    if ((mentionsUnits || (i >= 1 && words[i - 1] == "IN")) && !info.units) {
      if (const auto u = unitWord(w, i + 1 < words.size() ? std::string_view(words[i + 1]) : std::string_view{})) {
        info.units = u;
        info.unitsLine = line.number;
      }
    }
  }
}

bool isWholeNumber(double v) {
  return v >= 1.0 && v <= 1e9 && std::floor(v) == v;
}

}  // namespace

std::string_view groundMotionFormatName(GroundMotionFormat format) {
  switch (format) {
    case GroundMotionFormat::Auto:
      return "auto";
    case GroundMotionFormat::PeerAt2:
      return "PEER AT2";
    case GroundMotionFormat::ValuesOnly:
      return "values";
    case GroundMotionFormat::TimeAcceleration:
      return "time-acceleration";
  }
  return "?";
}

Result<GroundMotion> parseGroundMotion(std::string_view text, std::string_view name,
                                       const GroundMotionReadOptions& options, GroundMotionSource* source) {
  if (options.timeStepS &&
      !(std::isfinite(*options.timeStepS) && *options.timeStepS > 0.0 && *options.timeStepS <= 10.0)) {
    return errorAt(name, 0, "the time step given must be in (0, 10] s, not " + formatDouble(*options.timeStepS, 10));
  }
  if (const auto newlines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
      newlines >= kMaxLines) {
    return errorAt(name, 0,
                   "too many lines (more than " + std::to_string(kMaxLines) + "; a record holds at most " +
                       std::to_string(kMaxSamples) + " values)");
  }
  const std::vector<Line> lines = splitLines(text);

  // Header: the leading text lines (a value line cannot start before the first line that is all
  // numbers), plus an optional one-line numeric "NPTS DT" header recognised below.
  HeaderInfo header;
  std::size_t first = 0;
  std::vector<ParsedLine> parsed(lines.size());
  const auto tooManyValues = [&](std::size_t line) {
    return errorAt(name, line, "too many values (the limit is " + std::to_string(kMaxSamples) + ")");
  };
  for (; first < lines.size(); ++first) {
    parsed[first] = classify(lines[first].text);
    if (parsed[first].kind == LineKind::Numbers) break;
    if (parsed[first].kind == LineKind::Text) {
      scanHeaderLine(lines[first], header);
      parsed[first].values = {};  // numbers before the first word of a header line are not samples
    }
  }
  std::size_t valuesSeen = 0;
  for (std::size_t i = first; i < lines.size(); ++i) {
    if (i != first) parsed[i] = classify(lines[i].text);
    valuesSeen += parsed[i].values.size();
    if (parsed[i].tooManyValues || valuesSeen > kMaxSamples) return tooManyValues(lines[i].number);
    if (parsed[i].kind == LineKind::Text) {
      if (parsed[i].badIsNotFinite) {
        return errorAt(name, lines[i].number, "value '" + std::string(parsed[i].badToken) + "' is not a finite number");
      }
      return errorAt(name, lines[i].number, "not a number: '" + std::string(parsed[i].badToken) + "'");
    }
  }
  std::size_t valueLines = 0;
  std::size_t valueCount = 0;
  bool allTwo = true;
  std::size_t lastValueLine = 0;
  for (std::size_t i = first; i < lines.size(); ++i) {
    if (parsed[i].kind != LineKind::Numbers) continue;
    ++valueLines;
    valueCount += parsed[i].values.size();
    allTwo = allTwo && parsed[i].values.size() == 2;
    lastValueLine = lines[i].number;
  }
  if (valueCount == 0) {
    return errorAt(name, 0, text.empty() ? "the file is empty" : "no acceleration values in the file");
  }

  // A one-line numeric header "NPTS DT" (no text header): an integer count, a step, and exactly
  // that many values after it.
  std::size_t dataStart = first;
  if (!header.points && first < lines.size() && parsed[first].values.size() == 2 &&
      options.format != GroundMotionFormat::TimeAcceleration) {
    const double n = parsed[first].values[0];
    const double dt = parsed[first].values[1];
    if (isWholeNumber(n) && dt > 0.0 && dt <= 10.0 && static_cast<double>(valueCount - 2) == n) {
      header.points = n;
      header.pointsLine = lines[first].number;
      header.timeStepS = dt;
      header.timeStepLine = lines[first].number;
      dataStart = first + 1;
      valueCount -= 2;
      valueLines -= 1;
    }
  }

  GroundMotionFormat format = options.format;
  if (format == GroundMotionFormat::Auto) {
    if (header.points || header.timeStepS) {
      format = GroundMotionFormat::PeerAt2;
    } else if (allTwo && valueLines >= 2) {
      // Two columns when the first one is strictly increasing (times); otherwise values in pairs.
      bool increasing = true;
      double previous = -1e300;
      for (std::size_t i = dataStart; i < lines.size() && increasing; ++i) {
        if (parsed[i].kind != LineKind::Numbers) continue;
        increasing = parsed[i].values[0] > previous;
        previous = parsed[i].values[0];
      }
      format = increasing ? GroundMotionFormat::TimeAcceleration : GroundMotionFormat::ValuesOnly;
    } else {
      format = GroundMotionFormat::ValuesOnly;
    }
  }

  GroundMotion motion;
  motion.name = std::string(name);
  double timeStep = 0.0;
  bool timeStepFromFile = false;

  if (format == GroundMotionFormat::TimeAcceleration) {
    if (!allTwo) {
      for (std::size_t i = dataStart; i < lines.size(); ++i) {
        if (parsed[i].kind == LineKind::Numbers && parsed[i].values.size() != 2) {
          return errorAt(name, lines[i].number,
                         "expected two columns (time, acceleration), found " + std::to_string(parsed[i].values.size()) +
                             " values");
        }
      }
    }
    std::vector<double> times;
    std::vector<std::size_t> numbers;
    for (std::size_t i = dataStart; i < lines.size(); ++i) {
      if (parsed[i].kind != LineKind::Numbers) continue;
      times.push_back(parsed[i].values[0]);
      motion.accelerationMps2.push_back(parsed[i].values[1]);
      numbers.push_back(lines[i].number);
    }
    if (times.size() < 2) return errorAt(name, 0, "two-column records need at least two rows");
    timeStep = times[1] - times[0];
    if (!(timeStep > 0.0)) {
      return errorAt(
          name, numbers[1],
          "time does not increase (" + formatDouble(times[0], 10) + " then " + formatDouble(times[1], 10) + ")");
    }
    // The same bound as a header's DT (the difference of two finite times can even overflow).
    if (!(timeStep <= 10.0)) {
      return errorAt(name, numbers[1], "the times give a step of " + formatDouble(timeStep, 10) + " s (at most 10 s)");
    }
    // Times are printed with few digits: accept steps within 0.1 % of the first one.
    const double tolerance = 1e-3 * timeStep;
    for (std::size_t k = 1; k < times.size(); ++k) {
      const double step = times[k] - times[k - 1];
      if (std::fabs(step - timeStep) > tolerance) {
        return errorAt(name, numbers[k],
                       "non-uniform time step: " + formatDouble(step, 10) +
                           " s after t = " + formatDouble(times[k - 1], 10) + " s, the record started with " +
                           formatDouble(timeStep, 10) + " s");
      }
    }
    timeStepFromFile = true;
    // Placement on the time convention: a first row at t = 0 is the record's own a(0): dropped when
    // it is zero, otherwise every sample moves one step later. A first row at t = j·dt (j >= 1) is
    // preceded by j-1 zero samples so each value keeps its time.
    const double startSteps = times[0] / timeStep;
    const double nearest = std::round(startSteps);
    if (std::fabs(startSteps - nearest) > 1e-3 || nearest < 0.0 || nearest > 1e6) {
      return errorAt(name, numbers[0],
                     "the first time (" + formatDouble(times[0], 10) + " s) is not 0 or a multiple of the time step");
    }
    if (nearest == 0.0) {
      if (motion.accelerationMps2.front() == 0.0) motion.accelerationMps2.erase(motion.accelerationMps2.begin());
    } else if (nearest > 1.0) {
      motion.accelerationMps2.insert(motion.accelerationMps2.begin(), static_cast<std::size_t>(nearest) - 1, 0.0);
    }
    if (options.timeStepS && std::fabs(*options.timeStepS - timeStep) > 1e-6 * timeStep) {
      return errorAt(name, numbers[1],
                     "the times give a step of " + formatDouble(timeStep, 10) + " s but the step given is " +
                         formatDouble(*options.timeStepS, 10) + " s");
    }
  } else {
    motion.accelerationMps2.reserve(valueCount);
    for (std::size_t i = dataStart; i < lines.size(); ++i) {
      if (parsed[i].kind != LineKind::Numbers) continue;
      motion.accelerationMps2.insert(motion.accelerationMps2.end(), parsed[i].values.begin(), parsed[i].values.end());
    }
    if (header.points) {
      const double n = *header.points;
      if (!isWholeNumber(n)) {
        return errorAt(name, header.pointsLine, "NPTS must be a positive whole number, not " + formatDouble(n, 10));
      }
      if (static_cast<double>(motion.size()) != n) {
        return errorAt(name, header.pointsLine,
                       "NPTS = " + formatDouble(n, 10) + " in the header but " + std::to_string(motion.size()) +
                           " values follow (the last on line " + std::to_string(lastValueLine) + ")");
      }
    }
    if (header.timeStepS) {
      const double dt = *header.timeStepS;
      if (!(dt > 0.0 && dt <= 10.0)) {
        return errorAt(name, header.timeStepLine, "DT must be in (0, 10] s, not " + formatDouble(dt, 10));
      }
      if (options.timeStepS && std::fabs(*options.timeStepS - dt) > 1e-6 * dt) {
        return errorAt(name, header.timeStepLine,
                       "the header gives DT = " + formatDouble(dt, 10) + " s but the step given is " +
                           formatDouble(*options.timeStepS, 10) + " s");
      }
      timeStep = dt;
      timeStepFromFile = true;
    } else if (options.timeStepS) {
      timeStep = *options.timeStepS;
    } else {
      return errorAt(name, 0, "the file gives no time step: pass one (--dt)");
    }
  }

  // Units: the header's, checked against the caller's when both are given.
  AccelerationUnit units = AccelerationUnit::G;
  bool unitsFromFile = false;
  if (header.units) {
    if (options.units && *options.units != *header.units) {
      return errorAt(name, header.unitsLine,
                     "the header gives units " + std::string(accelerationUnitName(*header.units)) + " but " +
                         std::string(accelerationUnitName(*options.units)) + " was given");
    }
    units = *header.units;
    unitsFromFile = true;
  } else if (options.units) {
    units = *options.units;
  } else {
    return errorAt(name, 0, "the file does not state its units: pass them (--units g|m/s2|cm/s2)");
  }

  const double factor = metresPerSecond2Per(units);
  for (std::size_t k = 0; k < motion.accelerationMps2.size(); ++k) {
    double& a = motion.accelerationMps2[k];
    const double asWritten = a;
    a *= factor;
    // Values near the largest double overflow when converted; no record holds such a value.
    if (!std::isfinite(a)) {
      return errorAt(name, 0,
                     "sample " + std::to_string(k + 1) + " (" + formatDouble(asWritten, 10) + " " +
                         std::string(accelerationUnitName(units)) + ") is too large to be an acceleration");
    }
  }
  motion.timeStepS = timeStep;
  if (source != nullptr) {
    source->format = format;
    source->units = units;
    source->unitsFromFile = unitsFromFile;
    source->timeStepFromFile = timeStepFromFile;
  }
  return motion;
}

Result<GroundMotion> readGroundMotionFile(const std::string& path, const GroundMotionReadOptions& options,
                                          GroundMotionSource* source) {
  const std::size_t slash = path.find_last_of("/\\");
  const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) return errorAt(path, 0, "cannot open the file");
  std::string text;
  char buffer[1 << 16];
  bool tooBig = false;
  while (true) {
    const std::size_t n = std::fread(buffer, 1, sizeof buffer, file);
    if (n == 0) break;
    if (text.size() + n > kMaxFileBytes) {
      tooBig = true;
      break;
    }
    text.append(buffer, n);
  }
  const bool readError = std::ferror(file) != 0;
  std::fclose(file);
  if (readError) return errorAt(path, 0, "read error");
  if (tooBig) return errorAt(path, 0, "larger than the 256 MiB limit for a record");
  return parseGroundMotion(text, name, options, source);
}

}  // namespace qv::seismic
