// ShakeMap grid.xml reader. expat reads the XML (no DTD, no entities, nothing external) up to the
// <grid_data> start tag and is suspended there; the numbers (nearly all of the file) are then read
// straight from the buffer, row by row into the field vectors, up to the first '<', which must be
// </grid_data>; a second expat parser, re-opened on the same elements, reads the rest. Letting expat
// deliver the numbers as character data tripled the parse time (measured: 1.09 s for 1000 x 1000).
#include "qv/prep/ShakeMap.h"

#include <expat.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <system_error>

#include "qv/core/NumberFormat.h"
#include "qv/prep/Files.h"

namespace qv::prep {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Rows print coordinates with 4 decimals: a node is on the lattice within 1e-4 degrees (about 11 m).
constexpr double kLatticeToleranceDeg = 1e-4;
// expat is fed in pieces: it takes an int length, and when it is suspended at <grid_data> it copies
// the rest of the piece it was given, which should then be small.
constexpr std::size_t kParseChunkBytes = 256u << 10;

enum class Field { Lon, Lat, Pga, Pgv, Mmi, Psa03, Psa10, Psa30, Svel, Count };
constexpr std::size_t kFieldCount = static_cast<std::size_t>(Field::Count);
constexpr std::array<std::string_view, kFieldCount> kFieldNames = {"LON",   "LAT",   "PGA",   "PGV", "MMI",
                                                                   "PSA03", "PSA10", "PSA30", "SVEL"};

bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && isSpace(s.front())) s.remove_prefix(1);
  while (!s.empty() && isSpace(s.back())) s.remove_suffix(1);
  return s;
}

bool equalsIgnoreCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

/// The element's local name: "sm:grid_field" -> "grid_field".
std::string_view localName(const XML_Char* name) {
  std::string_view s(name);
  const auto colon = s.rfind(':');
  return colon == std::string_view::npos ? s : s.substr(colon + 1);
}

/// A whole number (leading '+' allowed, surrounding whitespace ignored); nullopt otherwise.
std::optional<double> parseNumber(std::string_view text) {
  text = trim(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return std::nullopt;
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

constexpr std::array<double, 23> kPowersOfTen = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                                 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

/// Reads the whitespace-delimited number starting at `p` (before `end`) into `value` and returns
/// the end of its token, or nullptr when the token is not a number. Plain decimals ("-74.0300",
/// "425.365") take Clinger's fast path in the same pass: a mantissa below 10^15 (< 2^53) divided by
/// an exact power of ten (<= 1e22) is one correctly rounded operation, so the result is the same
/// double as std::from_chars gives. Anything else (exponents, nan, inf, long digit strings) goes to
/// std::from_chars, which must consume the whole token.
const char* scanNumber(const char* p, const char* end, double& value) {
  if (*p == '+' && end - p > 1 && !isSpace(p[1])) ++p;
  const char* q = p;
  const bool negative = *q == '-';
  if (negative) ++q;
  const char* const digitsStart = q;
  std::uint64_t mantissa = 0;
  int digits = 0, fractionDigits = 0;
  bool point = false;
  for (; q != end; ++q) {
    const char c = *q;
    if (c >= '0' && c <= '9') {
      if (mantissa != 0 || c != '0') ++digits;
      mantissa = mantissa * 10 + static_cast<std::uint64_t>(c - '0');
      if (point) ++fractionDigits;
      if (digits > 15) break;
    } else if (c == '.' && !point) {
      point = true;
    } else {
      break;
    }
  }
  const auto length = q - digitsStart;
  if ((q == end || isSpace(*q)) && length > (point ? 1 : 0) && digits <= 15 && fractionDigits <= 22) {
    const double magnitude = static_cast<double>(mantissa) / kPowersOfTen[static_cast<std::size_t>(fractionDigits)];
    value = negative ? -magnitude : magnitude;
    return q;
  }
  const char* tokenEnd = q;
  while (tokenEnd != end && !isSpace(*tokenEnd)) ++tokenEnd;
  const auto [numberEnd, ec] = std::from_chars(p, tokenEnd, value);
  return ec == std::errc() && numberEnd == tokenEnd ? tokenEnd : nullptr;
}

std::string formatDegrees(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6f", value);
  std::string s(buffer);
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

/// What the file's values are divided by to give the stored unit (100 for percent g), or nullopt
/// for a unit this field cannot have.
std::optional<double> unitDivisor(Field field, std::string_view units) {
  units = trim(units);
  auto is = [&](std::string_view u) { return equalsIgnoreCase(units, u); };
  switch (field) {
    case Field::Lon:
    case Field::Lat:
      if (units.empty() || is("dd") || is("deg") || is("degrees")) return 1.0;
      return std::nullopt;
    case Field::Pga:
    case Field::Psa03:
    case Field::Psa10:
    case Field::Psa30:
      if (units.empty() || is("pctg") || is("%g")) return 100.0;
      if (is("g")) return 1.0;
      return std::nullopt;
    case Field::Pgv:
      if (units.empty() || is("cms") || is("cm/s")) return 1.0;
      return std::nullopt;
    case Field::Mmi:
      if (units.empty() || is("intensity")) return 1.0;
      return std::nullopt;
    case Field::Svel:
      if (units.empty() || is("ms") || is("m/s")) return 1.0;
      return std::nullopt;
    case Field::Count:
      break;
  }
  return std::nullopt;
}

std::string_view expectedUnits(Field field) {
  switch (field) {
    case Field::Lon:
    case Field::Lat:
      return "dd";
    case Field::Pga:
    case Field::Psa03:
    case Field::Psa10:
    case Field::Psa30:
      return "pctg, %g or g";
    case Field::Pgv:
      return "cms or cm/s";
    case Field::Mmi:
      return "intensity";
    case Field::Svel:
      return "ms or m/s";
    case Field::Count:
      break;
  }
  return "";
}

struct Column {
  std::optional<Field> field;  ///< nullopt: ignored
  double divisor = 1.0;
  bool declared = false;
};

class GridParser {
 public:
  GridParser(std::string_view name, const ShakeMapLimits& limits) : name_(name), limits_(limits) {}

  Result<ShakeMapGrid> parse(std::string_view xml) {
    if (xml.size() > limits_.maxBytes)
      return Error{name_ + ": " + std::to_string(xml.size()) + " bytes is more than the limit of " +
                   std::to_string(limits_.maxBytes) + " bytes for a ShakeMap grid"};
    if (trim(xml).empty()) return Error{name_ + ": empty file, not a ShakeMap grid.xml"};
    xml_ = xml;

    parser_ = newParser(nullptr);
    if (parser_ == nullptr) return Error{name_ + ": cannot create an XML parser (out of memory)"};
    bool failed = !feed(xml, 0);
    if (!failed && dataStart_ != 0) failed = !readGridData(xml) || !feedRest(xml);
    Result<ShakeMapGrid> result = failed ? Result<ShakeMapGrid>(Error{xmlFailure()}) : finish();
    XML_ParserFree(parser_);
    parser_ = nullptr;
    return result;
  }

 private:
  XML_Parser newParser(const char* encoding) {
    XML_Parser parser = XML_ParserCreate(encoding);
    if (parser == nullptr) return nullptr;
    XML_SetUserData(parser, this);
    XML_SetElementHandler(parser, &GridParser::onStart, &GridParser::onEnd);
    XML_SetXmlDeclHandler(parser, &GridParser::onXmlDecl);
    // No DTD at all: a DOCTYPE is where entity declarations (billion laughs, external entities)
    // live, and a grid.xml never has one. Refused before its internal subset is even read.
    XML_SetStartDoctypeDeclHandler(parser, &GridParser::onDoctype);
    XML_SetEntityDeclHandler(parser, &GridParser::onEntityDecl);
    XML_SetParamEntityParsing(parser, XML_PARAM_ENTITY_PARSING_NEVER);
    // No XML_SetExternalEntityRefHandler: expat then never loads anything external.
    return parser;
  }

  /// Feeds xml[offset..] to parser_ in pieces (expat takes an int length). False on an error;
  /// true when done or suspended at <grid_data> (dataStart_ set).
  bool feed(std::string_view xml, std::size_t offset) {
    do {
      const std::size_t piece = std::min(kParseChunkBytes, xml.size() - offset);
      const bool final = offset + piece == xml.size();
      const XML_Status status =
          XML_Parse(parser_, xml.data() + offset, static_cast<int>(piece), final ? XML_TRUE : XML_FALSE);
      if (status == XML_STATUS_SUSPENDED) return true;
      if (status != XML_STATUS_OK) return false;
      offset += piece;
    } while (offset < xml.size());
    return true;
  }

  /// The rows of <grid_data>, read from the buffer between the start tag and the first '<'.
  bool readGridData(std::string_view xml) {
    const std::size_t close = xml.find('<', dataStart_);
    const std::size_t end = close == std::string_view::npos ? xml.size() : close;
    std::uint64_t line = dataLine_;
    std::size_t at = dataStart_;
    while (at < end) {
      const char* begin = xml.data() + at;
      const void* found = std::memchr(begin, '\n', end - at);
      const std::size_t lineEnd =
          found == nullptr ? end : static_cast<std::size_t>(static_cast<const char*>(found) - xml.data());
      // A file cut off inside <grid_data>: its last, unfinished row is not read.
      if (found == nullptr && close == std::string_view::npos) break;
      row(std::string_view(begin, lineEnd - at), line);
      if (stopped()) return false;
      at = lineEnd + 1;
      if (found != nullptr) ++line;
    }
    if (close == std::string_view::npos) {
      stopAt(line, "the file ends inside <grid_data> after " + std::to_string(rows_) + " of " +
                       std::to_string(expectedRows_) + " rows (nlon x nlat = " + std::to_string(grid_.lonCount) +
                       " x " + std::to_string(grid_.latCount) + "): truncated grid");
      return false;
    }
    const std::string closeTag = "</" + dataTagName_;
    const std::string_view rest = xml.substr(close);
    const bool closed = rest.substr(0, closeTag.size()) == closeTag && rest.size() > closeTag.size() &&
                        (rest[closeTag.size()] == '>' || isSpace(rest[closeTag.size()]));
    if (!closed) {
      const std::size_t shown = std::min<std::size_t>(rest.find_first_of(" \t\r\n>"), 40);
      stopAt(line,
             "<grid_data> may hold only numbers and whitespace, found \"" + std::string(rest.substr(0, shown)) + "\"");
      return false;
    }
    dataEnd_ = close;
    dataEndLine_ = line;
    inGridData_ = false;
    if (rows_ < expectedRows_) {
      stopAt(line, "<grid_data> has " + std::to_string(rows_) +
                       " rows, expected nlon x nlat = " + std::to_string(grid_.lonCount) + " x " +
                       std::to_string(grid_.latCount) + " = " + std::to_string(expectedRows_) + ": truncated grid");
      return false;
    }
    return true;
  }

  /// The document after the grid's numbers: a new parser re-opens the elements that are open at
  /// <grid_data> (on one line, so its line numbers are offset by dataEndLine_ - 1), then reads on.
  bool feedRest(std::string_view xml) {
    XML_ParserFree(parser_);
    parser_ = newParser(encoding_.empty() ? nullptr : encoding_.c_str());
    if (parser_ == nullptr) {
      error_ = name_ + ": cannot create an XML parser (out of memory)";
      return false;
    }
    std::string reopen;
    for (const std::string& element : openElements_) reopen += "<" + element + ">";
    replaying_ = true;
    if (XML_Parse(parser_, reopen.data(), static_cast<int>(reopen.size()), XML_FALSE) != XML_STATUS_OK) return false;
    replaying_ = false;
    lineOffset_ = dataEndLine_ - 1;
    return feed(xml, dataEnd_);
  }

  // ---- expat callbacks ----
  static void XMLCALL onStart(void* self, const XML_Char* name, const XML_Char** attributes) {
    auto* parser = static_cast<GridParser*>(self);
    if (parser->replaying_) return;
    parser->openElements_.emplace_back(name);
    parser->start(localName(name), attributes);
  }
  static void XMLCALL onEnd(void* self, const XML_Char* name) {
    auto* parser = static_cast<GridParser*>(self);
    if (!parser->openElements_.empty()) parser->openElements_.pop_back();
    parser->end(localName(name));
  }
  static void XMLCALL onXmlDecl(void* self, const XML_Char*, const XML_Char* encoding, int) {
    if (encoding != nullptr) static_cast<GridParser*>(self)->encoding_ = encoding;
  }
  static void XMLCALL onDoctype(void* self, const XML_Char*, const XML_Char*, const XML_Char*, int) {
    static_cast<GridParser*>(self)->stop(
        "a DOCTYPE is not allowed in a ShakeMap grid.xml (entity declarations and external entities are refused)");
  }
  static void XMLCALL onEntityDecl(void* self, const XML_Char*, int, const XML_Char*, int, const XML_Char*,
                                   const XML_Char*, const XML_Char*, const XML_Char*) {
    static_cast<GridParser*>(self)->stop("entity declarations are not allowed in a ShakeMap grid.xml");
  }

  [[nodiscard]] std::uint64_t currentLine() const { return XML_GetCurrentLineNumber(parser_) + lineOffset_; }

  /// Records the first error at the current line and stops expat.
  void stop(const std::string& message) { stopAt(currentLine(), message); }
  void stopAt(std::uint64_t line, const std::string& message) {
    if (!error_.empty()) return;
    error_ = name_ + ":" + std::to_string(line) + ": " + message;
    XML_StopParser(parser_, XML_FALSE);
  }
  [[nodiscard]] bool stopped() const { return !error_.empty(); }

  std::string xmlFailure() {
    if (stopped()) return error_;
    const std::string line = std::to_string(currentLine());
    const std::string reason = XML_ErrorString(XML_GetErrorCode(parser_));
    if (!sawRoot_) return name_ + ":" + line + ": not XML, not a ShakeMap grid.xml (XML: " + reason + ")";
    return name_ + ":" + line + ": XML error: " + reason;
  }

  static std::optional<std::string_view> attribute(const XML_Char** attributes, std::string_view key) {
    for (std::size_t i = 0; attributes[i] != nullptr; i += 2)
      if (key == attributes[i]) return std::string_view(attributes[i + 1]);
    return std::nullopt;
  }
  static std::string text(const XML_Char** attributes, std::string_view key) {
    const auto value = attribute(attributes, key);
    return value ? std::string(*value) : std::string();
  }
  static double number(const XML_Char** attributes, std::string_view key) {
    const auto value = attribute(attributes, key);
    if (!value) return kNaN;
    const auto parsed = parseNumber(*value);
    return parsed && std::isfinite(*parsed) ? *parsed : kNaN;
  }

  void start(std::string_view element, const XML_Char** attributes) {
    if (stopped()) return;
    if (++depth_ > limits_.maxDepth) {
      stop("elements nested deeper than " + std::to_string(limits_.maxDepth) + " levels");
      return;
    }
    if (inGridData_) {
      stop("<" + std::string(element) + "> inside <grid_data>, which holds only numbers");
      return;
    }
    if (!sawRoot_) {
      sawRoot_ = true;
      if (element != "shakemap_grid") {
        stop("the root element is <" + std::string(element) + ">, not <shakemap_grid>: not a ShakeMap grid.xml");
        return;
      }
      readGridAttributes(attributes);
      return;
    }
    if (element == "event") {
      readEvent(attributes);
    } else if (element == "grid_specification") {
      readSpecification(attributes);
    } else if (element == "grid_field") {
      readField(attributes);
    } else if (element == "grid_data") {
      beginGridData();
    }
  }

  void end(std::string_view element) {
    if (stopped()) return;
    --depth_;
    if (element == "grid_data" && inGridData_) endGridData();
  }

  void readGridAttributes(const XML_Char** a) {
    ShakeMapEvent& e = grid_.event;
    e.eventId = text(a, "event_id");
    e.shakemapVersion = text(a, "shakemap_version");
    e.codeVersion = text(a, "code_version");
    e.processTimestamp = text(a, "process_timestamp");
    e.originator = text(a, "shakemap_originator");
    e.mapStatus = text(a, "map_status");
    const std::string_view type = trim(attribute(a, "shakemap_event_type").value_or(""));
    if (equalsIgnoreCase(type, "SCENARIO")) {
      e.type = ShakeMapEventType::Scenario;
    } else if (equalsIgnoreCase(type, "ACTUAL")) {
      e.type = ShakeMapEventType::Actual;
    }
  }

  void readEvent(const XML_Char** a) {
    ShakeMapEvent& e = grid_.event;
    if (e.eventId.empty()) e.eventId = text(a, "event_id");
    e.magnitude = number(a, "magnitude");
    e.depthKm = number(a, "depth");
    e.latitudeDeg = number(a, "lat");
    e.longitudeDeg = number(a, "lon");
    e.eventTimestamp = text(a, "event_timestamp");
    e.network = text(a, "event_network");
    e.description = text(a, "event_description");
  }

  std::optional<double> requiredNumber(const XML_Char** a, std::string_view key) {
    const auto value = attribute(a, key);
    if (!value) {
      stop("<grid_specification> has no " + std::string(key) + " attribute");
      return std::nullopt;
    }
    const auto parsed = parseNumber(*value);
    if (!parsed || !std::isfinite(*parsed)) {
      stop("<grid_specification> " + std::string(key) + "=\"" + std::string(*value) + "\" is not a finite number");
      return std::nullopt;
    }
    return parsed;
  }

  std::optional<std::size_t> requiredCount(const XML_Char** a, std::string_view key) {
    const auto value = attribute(a, key);
    if (!value) {
      stop("<grid_specification> has no " + std::string(key) + " attribute");
      return std::nullopt;
    }
    const std::string_view digits = trim(*value);
    std::uint64_t count = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), count);
    if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size()) {
      stop("<grid_specification> " + std::string(key) + "=\"" + std::string(*value) + "\" is not a whole number");
      return std::nullopt;
    }
    if (count < 2) {
      stop("<grid_specification> " + std::string(key) + "=" + std::to_string(count) +
           ": a grid needs at least 2 nodes in each direction");
      return std::nullopt;
    }
    return static_cast<std::size_t>(count);
  }

  /// The spacing between nodes from the extent; checks the nominal spacing against it.
  std::optional<double> spacing(const XML_Char** a, std::string_view axis, double minimum, double maximum,
                                std::size_t count) {
    const double step = (maximum - minimum) / static_cast<double>(count - 1);
    const std::string key = "nominal_" + std::string(axis) + "_spacing";
    const auto given = attribute(a, key);
    if (!given || trim(*given).empty()) return step;
    const auto nominal = parseNumber(*given);
    if (!nominal || !std::isfinite(*nominal) || *nominal <= 0.0) {
      stop("<grid_specification> " + key + "=\"" + std::string(*given) + "\" is not a positive number");
      return std::nullopt;
    }
    // The nominal spacing must reach the declared maximum within half a cell after count - 1 steps.
    if (std::fabs(*nominal * static_cast<double>(count - 1) - (maximum - minimum)) > 0.5 * step) {
      stop("<grid_specification> " + key + "=" + formatDouble(*nominal, 10) + " does not fit " + std::to_string(count) +
           " nodes from " + formatDouble(minimum, 10) + " to " + formatDouble(maximum, 10) + " (spacing " +
           formatDouble(step, 10) + ")");
      return std::nullopt;
    }
    return step;
  }

  void readSpecification(const XML_Char** a) {
    if (sawSpecification_) {
      stop("a second <grid_specification>");
      return;
    }
    sawSpecification_ = true;
    const auto lonMin = requiredNumber(a, "lon_min");
    if (!lonMin) return;
    const auto lonMax = requiredNumber(a, "lon_max");
    if (!lonMax) return;
    const auto latMin = requiredNumber(a, "lat_min");
    if (!latMin) return;
    const auto latMax = requiredNumber(a, "lat_max");
    if (!latMax) return;
    const auto nlon = requiredCount(a, "nlon");
    if (!nlon) return;
    const auto nlat = requiredCount(a, "nlat");
    if (!nlat) return;
    if (!(*lonMin < *lonMax) || *lonMin < -360.0 || *lonMax > 360.0) {
      stop("<grid_specification> lon_min " + formatDouble(*lonMin, 10) + " .. lon_max " + formatDouble(*lonMax, 10) +
           " is not an increasing longitude range");
      return;
    }
    if (!(*latMin < *latMax) || *latMin < -90.0 || *latMax > 90.0) {
      stop("<grid_specification> lat_min " + formatDouble(*latMin, 10) + " .. lat_max " + formatDouble(*latMax, 10) +
           " is not an increasing latitude range within -90..90");
      return;
    }
    if (*nlon > limits_.maxValues / *nlat) {
      stop("<grid_specification> nlon x nlat = " + std::to_string(*nlon) + " x " + std::to_string(*nlat) +
           " nodes is larger than the limit of " + std::to_string(limits_.maxValues) + " values");
      return;
    }
    const auto lonStep = spacing(a, "lon", *lonMin, *lonMax, *nlon);
    if (!lonStep) return;
    const auto latStep = spacing(a, "lat", *latMin, *latMax, *nlat);
    if (!latStep) return;
    grid_.lonMin = *lonMin;
    grid_.lonMax = *lonMax;
    grid_.latMin = *latMin;
    grid_.latMax = *latMax;
    grid_.lonCount = *nlon;
    grid_.latCount = *nlat;
    grid_.lonSpacing = *lonStep;
    grid_.latSpacing = *latStep;
  }

  void readField(const XML_Char** a) {
    if (sawGridData_) {
      stop("<grid_field> after <grid_data>");
      return;
    }
    const auto indexText = attribute(a, "index");
    const auto nameText = attribute(a, "name");
    if (!indexText || !nameText) {
      stop("<grid_field> needs index and name attributes");
      return;
    }
    const std::string_view digits = trim(*indexText);
    std::uint64_t index = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
    // More columns than this is no ShakeMap (they have 9 to a few dozen).
    if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size() || index < 1 || index > 1000) {
      stop("<grid_field name=\"" + std::string(*nameText) + "\"> index=\"" + std::string(*indexText) +
           "\" is not a column number 1..1000");
      return;
    }
    if (columns_.size() < index) columns_.resize(index);
    Column& column = columns_[index - 1];
    if (column.declared) {
      stop("two <grid_field> elements with index " + std::to_string(index));
      return;
    }
    column.declared = true;
    ++declaredColumns_;
    const std::string_view fieldName = trim(*nameText);
    for (std::size_t f = 0; f < kFieldCount; ++f) {
      if (!equalsIgnoreCase(fieldName, kFieldNames[f])) continue;
      const auto field = static_cast<Field>(f);
      if (fieldColumn_[f]) {
        stop("two <grid_field> elements named " + std::string(kFieldNames[f]));
        return;
      }
      const std::string_view units = attribute(a, "units").value_or("");
      const auto divisor = unitDivisor(field, units);
      if (!divisor) {
        stop("<grid_field name=\"" + std::string(kFieldNames[f]) + "\"> has unknown units \"" + std::string(units) +
             "\" (expected " + std::string(expectedUnits(field)) + ", or empty for the default)");
        return;
      }
      column.field = field;
      column.divisor = *divisor;
      fieldColumn_[f] = index - 1;
    }
  }

  std::vector<float>* storage(Field field) {
    switch (field) {
      case Field::Pga:
        return &grid_.pga;
      case Field::Pgv:
        return &grid_.pgv;
      case Field::Mmi:
        return &grid_.mmi;
      case Field::Psa03:
        return &grid_.psa03;
      case Field::Psa10:
        return &grid_.psa10;
      case Field::Psa30:
        return &grid_.psa30;
      case Field::Svel:
        return &grid_.vs30;
      default:
        return nullptr;
    }
  }

  void beginGridData() {
    if (sawGridData_) {
      stop("a second <grid_data>");
      return;
    }
    sawGridData_ = true;
    if (!sawSpecification_) {
      stop("<grid_data> without a <grid_specification> before it (nlon, nlat and the extent are needed)");
      return;
    }
    if (!checkFields()) return;
    const std::size_t nodes = grid_.lonCount * grid_.latCount;
    if (nodes > limits_.maxValues / columns_.size()) {
      stop("nlon x nlat x fields = " + std::to_string(grid_.lonCount) + " x " + std::to_string(grid_.latCount) + " x " +
           std::to_string(columns_.size()) + " values is larger than the limit of " +
           std::to_string(limits_.maxValues));
      return;
    }
    expectedRows_ = nodes;
    const XML_Index tagStart = XML_GetCurrentByteIndex(parser_);
    const int tagBytes = XML_GetCurrentByteCount(parser_);
    // Room for the rows the rest of the input can hold (a row takes at least 2 bytes per value), so
    // a small file declaring a huge grid allocates little before it is found truncated.
    const std::size_t restBytes = tagStart < 0 ? 0 : xml_.size() - static_cast<std::size_t>(tagStart);
    const std::size_t reserved = std::min(nodes, restBytes / (2 * columns_.size()));
    for (Column& column : columns_) {
      column.declared = false;
      std::vector<float>* values = column.field ? storage(*column.field) : nullptr;
      if (values != nullptr) values->reserve(reserved);
    }
    row_.resize(columns_.size());
    // <grid_data/>: no rows; the end handler reports the truncated grid.
    inGridData_ = true;
    if (tagStart < 0 || tagBytes < 2 ||
        xml_[static_cast<std::size_t>(tagStart) + static_cast<std::size_t>(tagBytes) - 2] == '/')
      return;
    dataStart_ = static_cast<std::size_t>(tagStart) + static_cast<std::size_t>(tagBytes);
    const auto tag = xml_.substr(static_cast<std::size_t>(tagStart), static_cast<std::size_t>(tagBytes));
    dataLine_ = currentLine() + static_cast<std::uint64_t>(std::count(tag.begin(), tag.end(), '\n'));
    dataTagName_ = openElements_.empty() ? std::string("grid_data") : openElements_.back();
    XML_StopParser(parser_, XML_TRUE);
  }

  bool checkFields() {
    if (columns_.empty()) {
      stop("<grid_data> without any <grid_field> before it");
      return false;
    }
    if (declaredColumns_ != columns_.size()) {
      for (std::size_t i = 0; i < columns_.size(); ++i)
        if (!columns_[i].declared) {
          stop("no <grid_field> with index " + std::to_string(i + 1) + " (the indices must be 1.." +
               std::to_string(columns_.size()) + ")");
          return false;
        }
    }
    for (const Field required : {Field::Lon, Field::Lat, Field::Pga}) {
      if (!fieldColumn_[static_cast<std::size_t>(required)]) {
        stop("no <grid_field name=\"" + std::string(kFieldNames[static_cast<std::size_t>(required)]) +
             "\">: a ShakeMap grid needs LON, LAT and PGA");
        return false;
      }
    }
    return true;
  }

  void endGridData() {
    inGridData_ = false;
    if (rows_ < expectedRows_)
      stop("<grid_data> has " + std::to_string(rows_) +
           " rows, expected nlon x nlat = " + std::to_string(grid_.lonCount) + " x " + std::to_string(grid_.latCount) +
           " = " + std::to_string(expectedRows_) + ": truncated grid");
  }

  /// One line of grid_data: a node's values, one per grid_field.
  void row(std::string_view line, std::uint64_t lineNumber) {
    const char* p = line.data();
    const char* const end = p + line.size();
    std::size_t count = 0;
    while (true) {
      while (p != end && isSpace(*p)) ++p;
      if (p == end) break;
      double value = 0.0;
      const char* tokenEnd = scanNumber(p, end, value);
      if (tokenEnd == nullptr) {
        tokenEnd = p;
        while (tokenEnd != end && !isSpace(*tokenEnd)) ++tokenEnd;
        stopAt(lineNumber, "value \"" + std::string(p, tokenEnd) + "\" of " + columnName(count) + " is not a number");
        return;
      }
      if (count < row_.size()) row_[count] = value;
      ++count;
      p = tokenEnd;
    }
    if (count == 0) return;  // a blank line
    if (count != row_.size()) {
      stopAt(lineNumber, "a row of " + std::to_string(count) + " values, expected " + std::to_string(row_.size()) +
                             " (one per <grid_field>)");
      return;
    }
    if (rows_ == expectedRows_) {
      stopAt(lineNumber, "more than nlon x nlat = " + std::to_string(grid_.lonCount) + " x " +
                             std::to_string(grid_.latCount) + " = " + std::to_string(expectedRows_) + " rows");
      return;
    }
    for (std::size_t i = 0; i < row_.size(); ++i) {
      if (!columns_[i].field) continue;
      if (!std::isfinite(row_[i])) {
        stopAt(lineNumber, columnName(i) + " value " + formatDouble(row_[i], 10) + " is not a finite number");
        return;
      }
      // Stored as float: a value beyond its range (1e300) would become infinite (found by fuzz_shakemap).
      if (std::fabs(row_[i] / columns_[i].divisor) > static_cast<double>(std::numeric_limits<float>::max())) {
        stopAt(lineNumber, columnName(i) + " value " + formatDouble(row_[i], 10) + " is out of range");
        return;
      }
    }
    // The node this row must be: longitude fastest, rows from lat_max down.
    const std::size_t column = rows_ % grid_.lonCount;
    const std::size_t gridRow = rows_ / grid_.lonCount;
    const double lon = row_[*fieldColumn_[static_cast<std::size_t>(Field::Lon)]];
    const double lat = row_[*fieldColumn_[static_cast<std::size_t>(Field::Lat)]];
    const double expectedLon = grid_.lonMin + static_cast<double>(column) * grid_.lonSpacing;
    const double expectedLat = grid_.latMax - static_cast<double>(gridRow) * grid_.latSpacing;
    if (std::fabs(lon - expectedLon) > kLatticeToleranceDeg || std::fabs(lat - expectedLat) > kLatticeToleranceDeg) {
      stopAt(lineNumber, "node (" + formatDouble(lon, 10) + ", " + formatDouble(lat, 10) + ") is off the grid: row " +
                             std::to_string(rows_ + 1) + " must be the node at lon " + formatDegrees(expectedLon) +
                             ", lat " + formatDegrees(expectedLat) + " (column " + std::to_string(column) + ", row " +
                             std::to_string(gridRow) +
                             " of the lattice; rows run longitude fastest, from lat_max down)");
      return;
    }
    for (std::size_t i = 0; i < row_.size(); ++i) {
      const Column& c = columns_[i];
      if (!c.field) continue;
      std::vector<float>* values = storage(*c.field);
      if (values == nullptr) continue;
      // Percent g is divided by 100 (not multiplied by 0.01): the nearest double to the g value.
      values->push_back(static_cast<float>(row_[i] / c.divisor));
    }
    ++rows_;
  }

  [[nodiscard]] std::string columnName(std::size_t i) const {
    std::string name = "column " + std::to_string(i + 1);
    if (i < columns_.size() && columns_[i].field)
      name += " (" + std::string(kFieldNames[static_cast<std::size_t>(*columns_[i].field)]) + ")";
    return name;
  }

  Result<ShakeMapGrid> finish() {
    const std::string where = name_ + ":" + std::to_string(currentLine()) + ": ";
    if (!sawSpecification_) return Error{where + "no <grid_specification> in the file: not a complete ShakeMap grid"};
    if (!sawGridData_) return Error{where + "no <grid_data> in the file: not a complete ShakeMap grid"};
    return std::move(grid_);
  }

  std::string name_;
  ShakeMapLimits limits_;
  XML_Parser parser_ = nullptr;
  std::string error_;
  ShakeMapGrid grid_;
  int depth_ = 0;
  bool sawRoot_ = false;
  bool sawSpecification_ = false;
  bool sawGridData_ = false;
  bool inGridData_ = false;
  std::vector<Column> columns_;
  std::size_t declaredColumns_ = 0;
  std::array<std::optional<std::size_t>, kFieldCount> fieldColumn_{};
  std::vector<double> row_;
  std::size_t rows_ = 0;
  std::size_t expectedRows_ = 0;
  std::string_view xml_;
  std::string encoding_;                   ///< from the XML declaration, for the second parser
  std::vector<std::string> openElements_;  ///< qualified names, outermost first
  bool replaying_ = false;                 ///< the second parser re-opening openElements_
  std::uint64_t lineOffset_ = 0;           ///< added to the second parser's line numbers
  std::size_t dataStart_ = 0;              ///< first byte after <grid_data>; 0 before it
  std::uint64_t dataLine_ = 0;             ///< line of dataStart_
  std::string dataTagName_;                ///< grid_data's qualified name, for its end tag
  std::size_t dataEnd_ = 0;                ///< the '<' of </grid_data>
  std::uint64_t dataEndLine_ = 0;
};

double interpolate(const std::vector<float>& values, std::size_t lonCount, std::size_t latCount, std::size_t row,
                   std::size_t column, double tx, double ty) {
  if (values.size() != lonCount * latCount) return kNaN;  // absent field
  const std::size_t i = row * lonCount + column;
  const double v00 = values[i], v01 = values[i + 1];
  const double v10 = values[i + lonCount], v11 = values[i + lonCount + 1];
  return (1.0 - ty) * ((1.0 - tx) * v00 + tx * v01) + ty * ((1.0 - tx) * v10 + tx * v11);
}

}  // namespace

std::string_view shakeMapEventTypeName(ShakeMapEventType type) {
  switch (type) {
    case ShakeMapEventType::Scenario:
      return "SCENARIO";
    case ShakeMapEventType::Actual:
      return "ACTUAL";
    case ShakeMapEventType::Unknown:
      break;
  }
  return "UNKNOWN";
}

bool ShakeMapGrid::hasSpectra() const {
  return !psa03.empty() && !psa10.empty() && !psa30.empty();
}

std::string ShakeMapGrid::describeExtent() const {
  return "lon " + formatDegrees(lonMin) + ".." + formatDegrees(lonMax) + ", lat " + formatDegrees(latMin) + ".." +
         formatDegrees(latMax) + " (" + std::to_string(lonCount) + " x " + std::to_string(latCount) + " nodes)";
}

Result<ShakeMapGrid> parseShakeMapGrid(std::string_view xml, std::string_view name, const ShakeMapLimits& limits) {
  GridParser parser(name, limits);
  return parser.parse(xml);
}

Result<ShakeMapGrid> readShakeMapGrid(const std::string& path, const ShakeMapLimits& limits) {
  const auto bytes = readFile(path, limits.maxBytes);
  if (!bytes.ok()) return Error{bytes.error()};
  return parseShakeMapGrid(std::string_view(reinterpret_cast<const char*>(bytes->data()), bytes->size()), path, limits);
}

std::optional<ShakeMapSample> sampleShakeMap(const ShakeMapGrid& grid, double longitudeDeg, double latitudeDeg) {
  if (grid.lonCount < 2 || grid.latCount < 2 || grid.pga.size() != grid.lonCount * grid.latCount) return std::nullopt;
  if (!(longitudeDeg >= grid.lonMin && longitudeDeg <= grid.lonMax && latitudeDeg >= grid.latMin &&
        latitudeDeg <= grid.latMax))
    return std::nullopt;  // also NaN
  // Cell (row, column) has its top-left node at row 0 = latMax; the last cell takes its far edge.
  const double fx = (longitudeDeg - grid.lonMin) / grid.lonSpacing;
  const double fy = (grid.latMax - latitudeDeg) / grid.latSpacing;
  const auto column = std::min(static_cast<std::size_t>(std::max(0.0, std::floor(fx))), grid.lonCount - 2);
  const auto row = std::min(static_cast<std::size_t>(std::max(0.0, std::floor(fy))), grid.latCount - 2);
  const double tx = std::clamp(fx - static_cast<double>(column), 0.0, 1.0);
  const double ty = std::clamp(fy - static_cast<double>(row), 0.0, 1.0);
  ShakeMapSample s;
  s.pgaG = interpolate(grid.pga, grid.lonCount, grid.latCount, row, column, tx, ty);
  s.pgvCmS = interpolate(grid.pgv, grid.lonCount, grid.latCount, row, column, tx, ty);
  s.mmi = interpolate(grid.mmi, grid.lonCount, grid.latCount, row, column, tx, ty);
  s.psa03G = interpolate(grid.psa03, grid.lonCount, grid.latCount, row, column, tx, ty);
  s.psa10G = interpolate(grid.psa10, grid.lonCount, grid.latCount, row, column, tx, ty);
  s.psa30G = interpolate(grid.psa30, grid.lonCount, grid.latCount, row, column, tx, ty);
  s.vs30Mps = interpolate(grid.vs30, grid.lonCount, grid.latCount, row, column, tx, ty);
  return s;
}

}  // namespace qv::prep
