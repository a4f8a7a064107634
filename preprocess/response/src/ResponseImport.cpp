#include "qv/prep/ResponseImport.h"

#include <simdjson.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <unordered_map>

#include "qv/core/NumberFormat.h"
#include "qv/format/CityTile.h"
#include "qv/format/Tileset.h"
#include "qv/prep/Cli.h"
#include "qv/prep/Files.h"
#include "qv/prep/HistoryEncoder.h"
#include "qv/seismic/BuildingModel.h"
#include "qv/seismic/Damage.h"

namespace qv::prep {
namespace {

// Two time steps are the same when they differ by less than this fraction (text round trips).
constexpr double kTimeTolerance = 1e-6;
/// Displacements beyond this (metres, after units) are not a building's: a wrong unit or garbage.
constexpr double kMaxDisplacementM = 1000.0;

// The import's single time step: set by the first building, checked for every other.
Status checkTimeStep(ImportedResults& results, double dt, const std::string& place) {
  if (!(dt > 0.0) || !std::isfinite(dt) || dt > 10.0) {
    return Error{place + ": time step " + formatDouble(dt, 9) + " s is not a positive step of at most 10 s"};
  }
  if (results.timeStepS == 0.0) {
    results.timeStepS = dt;
    results.timeStepPlace = place;
    return {};
  }
  if (std::abs(dt - results.timeStepS) > kTimeTolerance * results.timeStepS) {
    return Error{place + ": time step " + formatDouble(dt, 9) + " s differs from " +
                 formatDouble(results.timeStepS, 9) + " s (" + results.timeStepPlace +
                 "); all results of one import share one time base"};
  }
  return {};
}

Status checkStart(double start, const std::string& place) {
  if (!std::isfinite(start) || start < 0.0 || start > 1.0e5) {
    return Error{place + ": start time " + formatDouble(start, 9) +
                 " s is outside 0 .. 100000 s (the viewer's clock starts at 0)"};
  }
  return {};
}

Result<DisplacementUnit> resolveUnits(std::optional<std::string_view> fileUnits, std::optional<DisplacementUnit> given,
                                      const std::string& place) {
  if (!fileUnits) {
    if (!given) return Error{place + ": the file does not give its units; add them or pass --units m|cm|mm|in|ft"};
    return *given;
  }
  const auto unit = parseDisplacementUnit(*fileUnits);
  if (!unit)
    return Error{place + ": unknown length unit \"" + std::string(*fileUnits) + "\" (use m, cm, mm, in or ft)"};
  if (given && *given != *unit) {
    return Error{place + ": the file says its units are \"" + std::string(*fileUnits) + "\", --units says otherwise"};
  }
  return *unit;
}

// ---- JSON ---------------------------------------------------------------------------------------

namespace dom = simdjson::dom;

// One direction: an array of floor arrays (floor 1 first), each `frames` numbers long.
Status readJsonDirection(dom::element value, const std::string& path, double scale, ImportedBuilding& b,
                         std::vector<float>& out) {
  dom::array floors;
  if (value.get_array().get(floors) != simdjson::SUCCESS) {
    return Error{path + ": expected an array of floors (each an array of displacements)"};
  }
  std::size_t floorCount = 0;
  for (dom::element floor : floors) {
    (void)floor;
    ++floorCount;
  }
  if (floorCount == 0 || floorCount > 1000)
    return Error{path + ": " + std::to_string(floorCount) + " floors (1 .. 1000)"};
  if (b.floors != 0 && floorCount != b.floors) {
    return Error{path + ": " + std::to_string(floorCount) + " floors, the other direction has " +
                 std::to_string(b.floors)};
  }
  b.floors = floorCount;
  std::size_t i = 0;
  for (dom::element floor : floors) {
    const std::string floorPath = path + "[" + std::to_string(i) + "]";
    dom::array samples;
    if (floor.get_array().get(samples) != simdjson::SUCCESS) return Error{floorPath + ": expected an array of numbers"};
    const std::size_t count = samples.size();
    if (count < 2) return Error{floorPath + ": a history needs at least 2 samples, found " + std::to_string(count)};
    if (b.frames == 0) {
      b.frames = count;
    } else if (count != b.frames) {
      return Error{floorPath + ": " + std::to_string(count) + " samples, other floors of this building have " +
                   std::to_string(b.frames) + " (one time base per building)"};
    }
    if (out.empty()) out.assign(b.floors * b.frames, 0.0f);
    std::size_t f = 0;
    for (dom::element v : samples) {
      double d = 0.0;
      if (v.get_double().get(d) != simdjson::SUCCESS || !std::isfinite(d)) {
        return Error{floorPath + "[" + std::to_string(f) + "]: not a finite number"};
      }
      if (!(std::abs(d * scale) <= kMaxDisplacementM)) {
        return Error{floorPath + "[" + std::to_string(f) + "]: " + formatDouble(d, 9) +
                     " is not a building's displacement (more than 1 km; check the units)"};
      }
      out[f * b.floors + i] = static_cast<float>(d * scale);
      ++f;
    }
    ++i;
  }
  return {};
}

Status readJson(const std::string& path, std::optional<DisplacementUnit> units, ImportedResults& results) {
  simdjson::padded_string text;
  if (const auto e = simdjson::padded_string::load(path).get(text); e != simdjson::SUCCESS) {
    return Error{path + ": cannot read: " + simdjson::error_message(e)};
  }
  dom::parser parser;
  dom::element doc;
  if (const auto e = parser.parse(text).get(doc); e != simdjson::SUCCESS) {
    return Error{path + ": not valid JSON: " + simdjson::error_message(e)};
  }
  dom::object root;
  if (doc.get_object().get(root) != simdjson::SUCCESS) return Error{path + ": the top level must be an object"};
  std::string_view format;
  if (root["format"].get_string().get(format) == simdjson::SUCCESS && format != "quakeview-response-import") {
    return Error{path + ": format: \"" + std::string(format) + "\" is not \"quakeview-response-import\""};
  }
  std::int64_t version = 1;
  if (root["version"].error() != simdjson::NO_SUCH_FIELD &&
      (root["version"].get_int64().get(version) != simdjson::SUCCESS || version != 1)) {
    return Error{path + ": version: this build reads version 1"};
  }
  std::optional<std::string_view> fileUnits;
  if (root["units"].error() != simdjson::NO_SUCH_FIELD) {
    std::string_view u;
    if (root["units"].get_string().get(u) != simdjson::SUCCESS) return Error{path + ": units: expected a string"};
    fileUnits = u;
  }
  auto unit = resolveUnits(fileUnits, units, path + ": units");
  if (!unit.ok()) return Error{unit.error()};
  const double scale = metresPerDisplacementUnit(*unit);

  // The time base: "time_step_s" with per-building "start_s", or one "time_s" array for all.
  const bool hasStep = root["time_step_s"].error() != simdjson::NO_SUCH_FIELD;
  const bool hasTimes = root["time_s"].error() != simdjson::NO_SUCH_FIELD;
  if (hasStep == hasTimes) return Error{path + ": give exactly one of \"time_step_s\" and \"time_s\""};
  std::size_t timeCount = 0;
  double timeStart = 0.0;
  if (hasStep) {
    double dt = 0.0;
    if (root["time_step_s"].get_double().get(dt) != simdjson::SUCCESS) {
      return Error{path + ": time_step_s: expected a number"};
    }
    if (Status s = checkTimeStep(results, dt, path + ": time_step_s"); !s.ok()) return s;
  } else {
    dom::array times;
    if (root["time_s"].get_array().get(times) != simdjson::SUCCESS) {
      return Error{path + ": time_s: expected an array of times"};
    }
    std::vector<double> t;
    for (dom::element v : times) {
      double d = 0.0;
      if (v.get_double().get(d) != simdjson::SUCCESS || !std::isfinite(d)) {
        return Error{path + ": time_s[" + std::to_string(t.size()) + "]: not a finite number"};
      }
      t.push_back(d);
    }
    if (t.size() < 2) return Error{path + ": time_s: at least 2 times are needed"};
    const double dt = (t.back() - t.front()) / static_cast<double>(t.size() - 1);
    for (std::size_t k = 1; k < t.size(); ++k) {
      const double step = t[k] - t[k - 1];
      if (!(std::abs(step - dt) <= 1e-3 * dt)) {
        return Error{path + ": time_s[" + std::to_string(k) + "]: non-uniform time step (" + formatDouble(step, 9) +
                     " s here, " + formatDouble(dt, 9) + " s on average); resample to a uniform step"};
      }
    }
    if (Status s = checkTimeStep(results, dt, path + ": time_s"); !s.ok()) return s;
    if (Status s = checkStart(t.front(), path + ": time_s[0]"); !s.ok()) return s;
    timeCount = t.size();
    timeStart = t.front();
  }
  std::string_view motion;
  if (root["motion"].get_string().get(motion) == simdjson::SUCCESS && !motion.empty()) {
    if (!results.motion.empty()) results.motion += "; ";
    results.motion += motion;
  }

  dom::array buildings;
  if (root["buildings"].get_array().get(buildings) != simdjson::SUCCESS) {
    return Error{path + ": buildings: expected an array of building objects"};
  }
  std::size_t index = 0;
  for (dom::element item : buildings) {
    const std::string place = path + ": buildings[" + std::to_string(index++) + "]";
    dom::object o;
    if (item.get_object().get(o) != simdjson::SUCCESS) return Error{place + ": expected an object"};
    ImportedBuilding b;
    std::string_view id;
    if (o["id"].get_string().get(id) != simdjson::SUCCESS || id.empty()) {
      return Error{place + ".id: expected the building's id (w…, r…, s…, cj:…, g:…)"};
    }
    b.id = std::string(id);
    b.place = place + " (" + b.id + ")";
    b.startSeconds = timeStart;
    if (o["start_s"].error() != simdjson::NO_SUCH_FIELD) {
      if (hasTimes) return Error{place + ".start_s: not allowed with \"time_s\" (the times say when it starts)"};
      if (o["start_s"].get_double().get(b.startSeconds) != simdjson::SUCCESS) {
        return Error{place + ".start_s: expected a number"};
      }
      if (Status s = checkStart(b.startSeconds, place + ".start_s"); !s.ok()) return s;
    }
    if (o["pga_g"].error() != simdjson::NO_SUCH_FIELD) {
      double pga = 0.0;
      if (o["pga_g"].get_double().get(pga) != simdjson::SUCCESS || !(pga >= 0.0 && pga <= 10.0)) {
        return Error{place + ".pga_g: expected a peak ground acceleration in g (0 .. 10)"};
      }
      b.pgaG = pga;
    }
    if (o["x"].error() == simdjson::NO_SUCH_FIELD) return Error{place + ": \"x\" (floor displacements) is missing"};
    if (Status s = readJsonDirection(o["x"].value_unsafe(), place + ".x", scale, b, b.x); !s.ok()) return s;
    if (o["y"].error() != simdjson::NO_SUCH_FIELD) {
      if (Status s = readJsonDirection(o["y"].value_unsafe(), place + ".y", scale, b, b.y); !s.ok()) return s;
    }
    if (hasTimes && b.frames != timeCount) {
      return Error{place + ": " + std::to_string(b.frames) + " samples per floor, time_s has " +
                   std::to_string(timeCount)};
    }
    results.buildings.push_back(std::move(b));
  }
  return {};
}

// ---- CSV ----------------------------------------------------------------------------------------

std::vector<std::string_view> splitCsv(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= line.size(); ++i) {
    if (i == line.size() || line[i] == ',') {
      std::string_view field = line.substr(start, i - start);
      while (!field.empty() && (field.front() == ' ' || field.front() == '\t')) field.remove_prefix(1);
      while (!field.empty() && (field.back() == ' ' || field.back() == '\t' || field.back() == '\r')) {
        field.remove_suffix(1);
      }
      if (field.size() >= 2 && field.front() == '"' && field.back() == '"') field = field.substr(1, field.size() - 2);
      out.push_back(field);
      start = i + 1;
    }
  }
  return out;
}

struct CsvRow {
  double time;
  std::uint32_t floor;  // 1-based
  float x, y;
  std::size_t line;
};

Status readCsv(const std::string& path, std::optional<DisplacementUnit> units, ImportedResults& results) {
  auto text = readTextFile(path, 2ull << 30);
  if (!text.ok()) return Error{text.error()};
  std::string_view rest = *text;
  std::size_t lineNumber = 0;
  std::optional<std::string> fileUnits;
  std::size_t unitsLine = 0;
  std::string motion;
  int cBuilding = -1, cTime = -1, cFloor = -1, cX = -1, cY = -1;
  std::size_t columns = 0;
  std::vector<std::string> order;  // ids in order of first appearance
  std::unordered_map<std::string, std::vector<CsvRow>> rows;
  while (!rest.empty()) {
    const std::size_t end = rest.find('\n');
    std::string_view line = rest.substr(0, end);
    rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 1);
    ++lineNumber;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const std::string place = path + ":" + std::to_string(lineNumber);
    if (line.empty()) continue;
    if (line.front() == '#') {
      // "# key: value" metadata lines: units, motion.
      std::string_view body = line.substr(1);
      const std::size_t colon = body.find(':');
      if (colon == std::string_view::npos) continue;
      auto trim = [](std::string_view s) {
        while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
        while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
        return s;
      };
      const std::string_view key = trim(body.substr(0, colon)), value = trim(body.substr(colon + 1));
      if (key == "units") {
        fileUnits = std::string(value);
        unitsLine = lineNumber;
      } else if (key == "motion") {
        motion = std::string(value);
      }
      continue;
    }
    const auto fields = splitCsv(line);
    if (columns == 0) {  // the header
      columns = fields.size();
      for (std::size_t i = 0; i < fields.size(); ++i) {
        const std::string_view f = fields[i];
        const int c = static_cast<int>(i);
        if (f == "building" || f == "id")
          cBuilding = c;
        else if (f == "time_s" || f == "time")
          cTime = c;
        else if (f == "floor")
          cFloor = c;
        else if (f == "x")
          cX = c;
        else if (f == "y")
          cY = c;
        else
          return Error{place + ": unknown column \"" + std::string(f) + "\" (expected building,time_s,floor,x[,y])"};
      }
      if (cBuilding < 0 || cTime < 0 || cFloor < 0 || cX < 0) {
        return Error{place + ": the header needs the columns building, time_s, floor and x (y is optional)"};
      }
      continue;
    }
    if (fields.size() != columns) {
      return Error{place + ": " + std::to_string(fields.size()) + " fields, the header has " + std::to_string(columns)};
    }
    const std::string id(fields[static_cast<std::size_t>(cBuilding)]);
    if (id.empty()) return Error{place + ": empty building id"};
    const auto time = parseDouble(fields[static_cast<std::size_t>(cTime)]);
    if (!time)
      return Error{place + ": time \"" + std::string(fields[static_cast<std::size_t>(cTime)]) + "\" is not a number"};
    const auto floor = parseInteger(fields[static_cast<std::size_t>(cFloor)]);
    if (!floor || *floor < 1 || *floor > 1000) {
      return Error{place + ": floor \"" + std::string(fields[static_cast<std::size_t>(cFloor)]) +
                   "\" is not a floor number (1 is the first floor above ground)"};
    }
    const auto x = parseDouble(fields[static_cast<std::size_t>(cX)]);
    // (Finite, and within float range: the plausibility check follows once the units are known.)
    if (!x || !(std::abs(*x) <= 1e30))
      return Error{place + ": x \"" + std::string(fields[static_cast<std::size_t>(cX)]) + "\" is not a number"};
    double y = 0.0;
    if (cY >= 0) {
      const auto v = parseDouble(fields[static_cast<std::size_t>(cY)]);
      if (!v || !(std::abs(*v) <= 1e30))
        return Error{place + ": y \"" + std::string(fields[static_cast<std::size_t>(cY)]) + "\" is not a number"};
      y = *v;
    }
    auto [it, inserted] = rows.try_emplace(id);
    if (inserted) order.push_back(id);
    it->second.push_back(
        {*time, static_cast<std::uint32_t>(*floor), static_cast<float>(*x), static_cast<float>(y), lineNumber});
  }
  if (columns == 0) return Error{path + ": no header line (building,time_s,floor,x[,y])"};
  auto unit = resolveUnits(fileUnits ? std::optional<std::string_view>(*fileUnits) : std::nullopt, units,
                           fileUnits ? path + ":" + std::to_string(unitsLine) : path);
  if (!unit.ok()) return Error{unit.error()};
  const auto scale = static_cast<float>(metresPerDisplacementUnit(*unit));
  if (!motion.empty()) {
    if (!results.motion.empty()) results.motion += "; ";
    results.motion += motion;
  }

  for (const std::string& id : order) {
    std::vector<CsvRow>& r = rows[id];
    std::stable_sort(r.begin(), r.end(), [](const CsvRow& a, const CsvRow& b) {
      return a.time < b.time || (a.time == b.time && a.floor < b.floor);
    });
    ImportedBuilding b;
    b.id = id;
    b.place = path + ":" + std::to_string(r.front().line) + " (" + id + ")";
    std::uint32_t floors = 0;
    for (const CsvRow& row : r) floors = std::max(floors, row.floor);
    if (r.size() % floors != 0) {
      return Error{b.place + ": " + std::to_string(r.size()) + " rows do not make whole time steps of " +
                   std::to_string(floors) + " floors (every floor needs a value at every time)"};
    }
    b.floors = floors;
    b.frames = r.size() / floors;
    if (b.frames < 2) return Error{b.place + ": a history needs at least 2 time steps"};
    b.startSeconds = r.front().time;
    if (Status s = checkStart(b.startSeconds, path + ":" + std::to_string(r.front().line)); !s.ok()) return s;
    const double dt = (r.back().time - r.front().time) / static_cast<double>(b.frames - 1);
    b.x.resize(b.floors * b.frames);
    if (cY >= 0) b.y.resize(b.floors * b.frames);
    for (std::size_t f = 0; f < b.frames; ++f) {
      const double t = r[f * floors].time;
      for (std::uint32_t i = 0; i < floors; ++i) {
        const CsvRow& row = r[f * floors + i];
        const std::string where = path + ":" + std::to_string(row.line);
        if (row.floor != i + 1 || row.time != t) {
          return Error{where + ": building " + id + " has no value for floor " + std::to_string(i + 1) + " at t = " +
                       formatDouble(t, 9) + " s, or two for another (every floor needs one value at every time)"};
        }
        if (!(std::abs(t - (b.startSeconds + static_cast<double>(f) * dt)) <= 1e-3 * dt)) {
          return Error{where + ": non-uniform time step for building " + id + " at t = " + formatDouble(t, 9) +
                       " s (expected " + formatDouble(b.startSeconds + static_cast<double>(f) * dt, 9) +
                       " s); resample to a uniform step"};
        }
        for (const double v : {static_cast<double>(row.x), cY >= 0 ? static_cast<double>(row.y) : 0.0}) {
          if (!(std::abs(v * scale) <= kMaxDisplacementM)) {
            return Error{where + ": " + formatDouble(v, 9) +
                         " is not a building's displacement (more than 1 km; check the units)"};
          }
        }
        b.x[f * floors + i] = static_cast<float>(row.x * scale);
        if (cY >= 0) b.y[f * floors + i] = static_cast<float>(row.y * scale);
      }
    }
    if (Status s = checkTimeStep(results, dt, b.place); !s.ok()) return s;
    results.buildings.push_back(std::move(b));
  }
  return {};
}

}  // namespace

std::optional<DisplacementUnit> parseDisplacementUnit(std::string_view t) {
  if (t == "m" || t == "metre" || t == "metres" || t == "meter" || t == "meters") return DisplacementUnit::Metre;
  if (t == "cm") return DisplacementUnit::Centimetre;
  if (t == "mm") return DisplacementUnit::Millimetre;
  if (t == "in" || t == "inch" || t == "inches") return DisplacementUnit::Inch;
  if (t == "ft" || t == "foot" || t == "feet") return DisplacementUnit::Foot;
  return std::nullopt;
}

double metresPerDisplacementUnit(DisplacementUnit unit) {
  switch (unit) {
    case DisplacementUnit::Centimetre:
      return 0.01;
    case DisplacementUnit::Millimetre:
      return 0.001;
    case DisplacementUnit::Inch:
      return 0.0254;
    case DisplacementUnit::Foot:
      return 0.3048;
    default:
      return 1.0;
  }
}

Status readImportedResponse(const std::string& path, std::optional<DisplacementUnit> units, ImportedResults& results) {
  auto head = readFile(path, 2ull << 30);
  if (!head.ok()) return Error{head.error()};
  for (std::uint8_t c : *head) {
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n') continue;
    return c == '{' ? readJson(path, units, results) : readCsv(path, units, results);
  }
  return Error{path + ": the file is empty"};
}

DisplacementSummary summarizeDisplacements(const BuildingAttributes& a, std::span<const float> x,
                                           std::span<const float> y, std::size_t floors, std::size_t frames, double dt,
                                           double startSeconds, double tolerance) {
  DisplacementSummary out;
  BuildingResult& r = out.result;
  // Storey heights and damage thresholds as the MDOF path has them (the building's model); a
  // building whose attributes give no model falls back to equal storeys of its height.
  std::vector<double> heights(floors, 3.0);
  std::array<double, 4> thresholds =
      seismic::hazusDriftThresholds(a.structuralType, a.codeEra, static_cast<int>(floors));
  if (auto model = seismic::buildingModelFromAttributes(a); model.ok() && model->storeyHeightM.size() == floors) {
    heights = model->storeyHeightM;
    thresholds = model->damageDriftThresholds;
  } else if (a.heightM > 0.0f) {
    std::fill(heights.begin(), heights.end(), static_cast<double>(a.heightM) / static_cast<double>(floors));
  }
  r.storeyPeakDrift.assign(floors, 0.0f);
  float residual = 0.0f;
  for (const std::span<const float> d : {x, y}) {
    if (d.empty()) continue;
    for (std::size_t f = 0; f < frames; ++f) {
      const float* v = d.data() + f * floors;
      for (std::size_t i = 0; i < floors; ++i) {
        const float drift = std::abs(v[i] - (i > 0 ? v[i - 1] : 0.0f)) / static_cast<float>(heights[i]);
        r.storeyPeakDrift[i] = std::max(r.storeyPeakDrift[i], drift);
        if (f + 1 == frames) residual = std::max(residual, drift);
      }
    }
  }
  EncodedHistory h;
  HistoryEncodingOptions encoding;
  encoding.toleranceFraction = tolerance;
  h = encodeHistory(x, y, floors, frames, dt, encoding);
  h.history.startSeconds += static_cast<float>(startSeconds);
  out.relativeError = h.relativeError();
  r.history = std::move(h.history);
  float peakDrift = 0.0f;
  for (float v : r.storeyPeakDrift) peakDrift = std::max(peakDrift, v);
  r.summary.source = ResponseSource::Imported;
  r.summary.storeys = static_cast<std::uint16_t>(floors);
  r.summary.peakDriftRatio = peakDrift;
  r.summary.peakRoofDisplacementM = static_cast<float>(h.peakRoofM);
  r.summary.residualDriftRatio = residual;
  r.summary.damage = seismic::classifyDamage(peakDrift, thresholds);
  return out;
}

Result<ImportReport> runImportResponse(const std::string& dir, const ImportOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  ImportReport report;
  if (options.inputs.empty()) return Error{"no input files"};
  auto text = readTextFile(dir + "/tileset.json", 256ull << 20);
  if (!text.ok()) return Error{text.error() + " (is " + dir + " a QuakeView city directory?)"};
  auto parsed = parseTileset(*text, dir + "/tileset.json");
  if (!parsed.ok()) return Error{parsed.error()};
  const Tileset tileset = std::move(parsed).value();

  ImportedResults results;
  for (const std::string& input : options.inputs) {
    if (Status s = readImportedResponse(input, options.units, results); !s.ok()) return Error{s.error()};
    if (interrupted()) return Error{"interrupted; the city's previous response is unchanged"};
  }
  std::unordered_map<std::string, std::size_t> byId;
  for (std::size_t i = 0; i < results.buildings.size(); ++i) {
    const auto [it, inserted] = byId.emplace(results.buildings[i].id, i);
    if (!inserted) {
      return Error{results.buildings[i].place + ": building " + results.buildings[i].id + " already has results (" +
                   results.buildings[it->second].place + ")"};
    }
  }
  report.timeStepS = results.timeStepS;
  report.motion = results.motion.empty() ? "imported displacement histories" : results.motion;

  auto writer = ResponseWriter::create(dir, tileset);
  if (!writer.ok()) return Error{writer.error()};
  std::vector<bool> used(results.buildings.size(), false);
  std::vector<double> errors;
  double rateSum = 0.0;
  for (std::uint32_t node = 0; node < tileset.nodes.size(); ++node) {
    const TileNode& n = tileset.nodes[node];
    if (!n.children.empty()) continue;
    if (interrupted()) return Error{"interrupted; the city's previous response is unchanged"};
    auto bytes = readFile(dir + "/" + n.file);
    if (!bytes.ok()) return Error{bytes.error()};
    auto tile = decodeCityTile(*bytes, dir + "/" + n.file);
    if (!tile.ok()) return Error{tile.error()};
    std::vector<BuildingResult> leafResults(tile->buildings.size());
    for (std::size_t b = 0; b < tile->buildings.size(); ++b) {
      const BuildingAttributes& a = tile->buildings[b].attributes;
      ++report.buildings;
      const auto it = byId.find(a.id);
      if (it == byId.end()) {
        if (report.missing.size() < options.listMissing) report.missing.push_back(a.id);
        leafResults[b].summary.noResultReason = NoResultReason::NotInImport;
        continue;
      }
      ImportedBuilding& in = results.buildings[it->second];
      if (in.floors != a.storeys) {
        return Error{in.place + ": " + std::to_string(in.floors) + " floors of results, the city's building " + a.id +
                     " has " + std::to_string(a.storeys) + " storeys"};
      }
      used[it->second] = true;
      DisplacementSummary s = summarizeDisplacements(a, in.x, in.y, in.floors, in.frames, results.timeStepS,
                                                     in.startSeconds, options.historyTolerance);
      if (in.pgaG) s.result.summary.pgaG = static_cast<float>(*in.pgaG);
      errors.push_back(s.relativeError);
      rateSum += s.result.history.sampleRateHz;
      report.durationSeconds =
          std::max(report.durationSeconds, in.startSeconds + static_cast<double>(in.frames - 1) * results.timeStepS);
      leafResults[b] = std::move(s.result);
      ++report.imported;
      // The histories are no longer needed: keep peak memory to one copy of the input.
      in.x = {};
      in.y = {};
    }
    if (Status s = (*writer)->writeLeaf(node, *tile, leafResults); !s.ok()) return Error{s.error()};
  }
  for (std::size_t i = 0; i < used.size(); ++i) {
    if (!used[i]) {
      return Error{results.buildings[i].place + ": building '" + results.buildings[i].id + "' is not in the city " +
                   dir + " (ids are w…, r…, s…, cj:…, g:… as `info --building` shows)"};
    }
  }
  ResponseInfo info;
  info.motion = report.motion;
  info.method = "imported per-floor displacement histories";
  info.durationSeconds = report.durationSeconds;
  info.sampleRateHz = report.imported > 0 ? rateSum / static_cast<double>(report.imported) : 0.0;
  auto written = (*writer)->commit(info);
  if (!written.ok()) return Error{written.error()};
  for (int k = 0; k < 6; ++k) report.damage[k] = written->damage[k];
  report.summaryBytes = written->summaryBytes;
  report.historyBytes = written->historyBytes;
  report.folder = written->folder;
  if (!errors.empty()) {
    std::sort(errors.begin(), errors.end());
    report.worstRelativeError = errors.back();
    report.p99RelativeError = errors[static_cast<std::size_t>(0.99 * static_cast<double>(errors.size() - 1))];
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace qv::prep
