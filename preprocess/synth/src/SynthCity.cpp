#include "qv/prep/SynthCity.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "qv/core/SplitMix64.h"
#include "qv/prep/Attributes.h"

namespace qv::prep {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Street grid: blocks of 100 m × 64 m (long side east-west) between 18 m streets and 30 m avenues.
constexpr double kBlockWidth = 100.0;
constexpr double kBlockDepth = 64.0;
constexpr double kStreet = 18.0;
constexpr double kAvenue = 30.0;
constexpr double kPitchX = kBlockWidth + kAvenue;
constexpr double kPitchY = kBlockDepth + kStreet;

std::uint64_t rotl(std::uint64_t x, int k) {
  return (x << k) | (x >> (64 - k));
}

// Block (i, j) of the square spiral around the centre, in the order the city grows.
void spiral(std::uint64_t index, long& i, long& j) {
  if (index == 0) {
    i = j = 0;
    return;
  }
  // Ring r holds 8r blocks, starting after (2r-1)² earlier ones.
  const auto r = static_cast<long>(std::ceil((std::sqrt(static_cast<double>(index) + 1.0) - 1.0) / 2.0));
  const long side = 2 * r;
  const long first = (2 * r - 1) * (2 * r - 1);
  const long k = static_cast<long>(index) - first;
  if (k < side) {
    i = r;
    j = -r + 1 + k;
  } else if (k < 2 * side) {
    i = r - 1 - (k - side);
    j = r;
  } else if (k < 3 * side) {
    i = -r;
    j = r - 1 - (k - 2 * side);
  } else {
    i = -r + 1 + (k - 3 * side);
    j = -r;
  }
}

struct Lot {
  double x0, y0, x1, y1;  // axis-aligned lot rectangle
};

std::string ordinal(long n) {
  const long lastTwo = n % 100;
  const char* suffix = "th";
  if (lastTwo < 11 || lastTwo > 13) {
    if (n % 10 == 1)
      suffix = "st";
    else if (n % 10 == 2)
      suffix = "nd";
    else if (n % 10 == 3)
      suffix = "rd";
  }
  return std::to_string(n) + suffix;
}

// Counter-clockwise rectangle.
void addRect(std::vector<glm::dvec2>& pts, double x0, double y0, double x1, double y1) {
  pts.insert(pts.end(), {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
}

/// Gives the `count` tallest rectangular and L-shaped buildings setbacks: a podium over the whole
/// footprint up to about a quarter of the height, then over the footprint's main rectangle (all of
/// a rectangle; an L's wing without the notch) a shaft inset by 15 % of its shorter side up to
/// about three quarters and a crown inset by 30 % to the roof. Part heights fall on floor levels.
void makeDetailedTowers(CityModel& model, std::uint64_t count) {
  if (count == 0) return;
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < model.buildings.size(); ++i) {
    const Building& b = model.buildings[i];
    if (b.attributes.storeys >= kMinTowerStoreys && b.parts.size() == 1 && b.parts[0].ringEnds.size() == 1 &&
        (b.parts[0].points.size() == 4 || b.parts[0].points.size() == 6)) {
      candidates.push_back(i);
    }
  }
  const std::size_t n = std::min<std::size_t>(candidates.size(), count);
  std::partial_sort(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(n), candidates.end(),
                    [&model](std::size_t a, std::size_t b) {
                      const float ha = model.buildings[a].attributes.heightM;
                      const float hb = model.buildings[b].attributes.heightM;
                      return ha != hb ? ha > hb : a < b;
                    });
  for (std::size_t k = 0; k < n; ++k) {
    Building& b = model.buildings[candidates[k]];
    const BuildingAttributes& a = b.attributes;
    const BuildingPart whole = b.parts[0];
    double x0 = whole.points[0].x, y0 = whole.points[0].y, x1 = x0, y1 = y0;
    for (const glm::dvec2& p : whole.points) {
      x0 = std::min(x0, p.x);
      y0 = std::min(y0, p.y);
      x1 = std::max(x1, p.x);
      y1 = std::max(y1, p.y);
    }
    if (whole.points.size() == 6) {
      // An L (generateSynthCity's: the rectangle minus a corner notch; points[2]'s
      // y is the notch's depth): the main rectangle is the full-width strip beside the notch.
      const glm::dvec2 inner = whole.points[2];
      if (inner.y > y0 + 1e-9 && inner.y < y1 - 1e-9) {
        if (std::abs(whole.points[1].x - x1) < 1e-9) {
          y1 = inner.y;  // notch at the back (high y): keep the front
        } else {
          y0 = inner.y;  // notch at the front (low y): keep the back
        }
      }
    }
    const double storeyM = static_cast<double>(a.heightM) / a.storeys;
    const int podiumTop = std::max(1, static_cast<int>(std::lround(a.storeys * 0.25)));
    const int shaftTop = std::max(podiumTop + 1, static_cast<int>(std::lround(a.storeys * 0.75)));
    const double side = std::min(x1 - x0, y1 - y0);
    b.parts.clear();
    const struct {
      const char* name;
      double inset;
      int bottom, top;
    } pieces[3] = {
        {"podium", 0.0, 0, podiumTop}, {"shaft", 0.15, podiumTop, shaftTop}, {"crown", 0.30, shaftTop, a.storeys}};
    for (const auto& piece : pieces) {
      if (piece.top <= piece.bottom) continue;
      BuildingPart part;
      const double m = side * piece.inset;
      addRect(part.points, x0 + m, y0 + m, x1 - m, y1 - m);
      part.ringEnds = {4};
      part.minHeightM = static_cast<float>(storeyM * piece.bottom);
      part.heightM = piece.top == a.storeys ? a.heightM : static_cast<float>(storeyM * piece.top);
      part.sourceId = a.id + "/" + piece.name;
      b.parts.push_back(std::move(part));
    }
  }
}

// ---- The map (docs/synth-city.md "Map").

/// The range of one grid column's (or row's) blocks, which the square spiral keeps contiguous.
struct BlockRange {
  long lo = 1, hi = 0;  // empty while lo > hi
  void add(long v) {
    if (empty()) {
      lo = hi = v;
    } else {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  void add(const BlockRange& r) {
    if (r.lo > r.hi) return;
    add(r.lo);
    add(r.hi);
  }
  [[nodiscard]] bool empty() const { return lo > hi; }
};

/// Park names for the empty blocks, nearest the centre first; the blocks after these have none.
constexpr const char* kParkNames[] = {
    "Linden Square", "Founders Park",  "Maple Green",    "Harbor Square", "Union Park",     "Chestnut Green",
    "Mill Park",     "Orchard Square", "Willow Park",    "Market Green",  "Lantern Square", "Elm Park",
    "Beacon Green",  "Garden Square",  "Cedar Park",     "Quarry Green",  "Meadow Square",  "Ash Park",
    "Foundry Green", "Station Park",   "Hawthorn Green", "Bell Square",   "Juniper Park",   "Commons Green",
};

/// Neighbourhood names by compass direction from the centre (east first, counter-clockwise).
constexpr const char* kQuarterNames[8] = {"Eastbank",  "Harbor Heights", "Northgate", "Hillcrest",
                                          "Westfield", "Millbrook",      "Southside", "Riverside"};

/// The avenues, streets, parks, river and neighbourhoods of a city whose blocks are the spiral's
/// first `blocks`, of which `parks` (spiral order) have no buildings.
GroundFeatures synthGround(std::uint64_t blocks, const std::vector<std::pair<long, long>>& parks) {
  GroundFeatures g;
  long radius = 0;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    long i = 0, j = 0;
    spiral(b, i, j);
    radius = std::max({radius, std::labs(i), std::labs(j)});
  }
  // Column i's blocks span rows columns[i + radius], row j's span columns rows[j + radius].
  std::vector<BlockRange> columns(static_cast<std::size_t>(2 * radius + 1));
  std::vector<BlockRange> rows(columns.size());
  for (std::uint64_t b = 0; b < blocks; ++b) {
    long i = 0, j = 0;
    spiral(b, i, j);
    columns[static_cast<std::size_t>(i + radius)].add(j);
    rows[static_cast<std::size_t>(j + radius)].add(i);
  }
  auto rangeOf = [radius](const std::vector<BlockRange>& ranges, long k) {
    return k < -radius || k > radius ? BlockRange{} : ranges[static_cast<std::size_t>(k + radius)];
  };
  BlockRange allColumns, allRows;
  for (long k = -radius; k <= radius; ++k) {
    if (!rangeOf(columns, k).empty()) allColumns.add(k);
    if (!rangeOf(rows, k).empty()) allRows.add(k);
  }

  // Avenues run north-south between columns i and i + 1, numbered from the west; every third is a
  // major one. They reach as far as the blocks beside them.
  for (long i = allColumns.lo - 1; i <= allColumns.hi; ++i) {
    BlockRange along = rangeOf(columns, i);
    along.add(rangeOf(columns, i + 1));
    const long number = i - allColumns.lo + 2;
    const bool major = number % 3 == 0;
    const double x = (static_cast<double>(i) + 0.5) * kPitchX;
    GroundLine avenue;
    avenue.groundClass = major ? GroundClass::Major : GroundClass::Street;
    avenue.widthM = major ? 20.0f : 14.0f;
    avenue.rank = major ? 40 : 88;
    avenue.name = ordinal(number) + " Avenue";
    avenue.points = {{x, (static_cast<double>(along.lo) - 0.5) * kPitchY},
                     {x, (static_cast<double>(along.hi) + 0.5) * kPitchY}};
    g.lines.push_back(std::move(avenue));
  }
  // Streets run east-west between rows j and j + 1, named as the addresses of the lots of row j
  // that face them ("North 14th Street"); every fifth is a major one.
  for (long j = allRows.lo - 1; j <= allRows.hi; ++j) {
    BlockRange along = rangeOf(rows, j);
    along.add(rangeOf(rows, j + 1));
    const long street = 2 * j + 1;
    const long number = std::labs(street) + 1;
    const bool major = number % 10 == 4;
    const double y = (static_cast<double>(j) + 0.5) * kPitchY;
    GroundLine crossStreet;
    crossStreet.groundClass = major ? GroundClass::Major : GroundClass::Street;
    crossStreet.widthM = major ? 14.0f : 10.0f;
    crossStreet.rank = major ? 48 : 104;
    crossStreet.name = (street >= 0 ? "North " : "South ") + ordinal(number) + " Street";
    crossStreet.points = {{(static_cast<double>(along.lo) - 0.5) * kPitchX, y},
                          {(static_cast<double>(along.hi) + 0.5) * kPitchX, y}};
    g.lines.push_back(std::move(crossStreet));
  }

  // The empty blocks are parks.
  for (std::size_t k = 0; k < parks.size(); ++k) {
    const double bx = static_cast<double>(parks[k].first) * kPitchX - kBlockWidth / 2;
    const double by = static_cast<double>(parks[k].second) * kPitchY - kBlockDepth / 2;
    GroundArea park;
    park.groundClass = GroundClass::Park;
    park.rank = 112;
    park.name = k < std::size(kParkNames) ? kParkNames[k] : "";
    park.rings.emplace_back();
    addRect(park.rings[0], bx, by, bx + kBlockWidth, by + kBlockDepth);
    g.areas.push_back(std::move(park));
  }

  // A river beyond the east edge, about a twentieth of the city wide (150 .. 600 m), its banks
  // meandering gently, running a fifth of the city's length past it north and south; between the
  // last avenue and the river a riverside park 40 m wide at its narrowest.
  const double south = (static_cast<double>(allRows.lo) - 0.5) * kPitchY;
  const double north = (static_cast<double>(allRows.hi) + 0.5) * kPitchY;
  const double west = (static_cast<double>(allColumns.lo) - 0.5) * kPitchX;
  const double east = (static_cast<double>(allColumns.hi) + 0.5) * kPitchX;
  const double span = std::max(north - south, east - west);
  const double riverWidth = std::clamp(0.05 * span, 150.0, 600.0);
  const double parkWest = east + kAvenue / 2;
  const double bank = parkWest + 40.0;
  const double amplitude = 30.0;
  const double wavelength = std::max(1500.0, span / 3);
  const double from = south - 0.2 * span - riverWidth;
  const double to = north + 0.2 * span + riverWidth;
  auto bankAt = [&](double y) {
    return glm::dvec2{bank + amplitude * (1.0 - std::cos(2.0 * kPi * (y - from) / wavelength)), y};
  };
  const auto steps = static_cast<int>(std::ceil((to - from) / 50.0));
  std::vector<glm::dvec2> westBank;
  for (int k = 0; k <= steps; ++k) westBank.push_back(bankAt(from + (to - from) * k / steps));
  GroundArea river;
  river.groundClass = GroundClass::Water;
  river.rank = 24;
  river.name = "Synthetic River";
  river.rings.emplace_back();
  std::vector<glm::dvec2>& water = river.rings[0];
  for (auto it = westBank.rbegin(); it != westBank.rend(); ++it) water.push_back(*it);  // north to south
  for (const glm::dvec2& p : westBank) water.push_back({p.x + riverWidth, p.y});        // south to north
  g.areas.push_back(std::move(river));
  GroundArea riverside;
  riverside.groundClass = GroundClass::Park;
  riverside.rank = 96;
  riverside.name = "Riverside Park";
  riverside.rings.emplace_back();
  std::vector<glm::dvec2>& strip = riverside.rings[0];
  strip.push_back(bankAt(south));  // south to north along the river, then back along the avenue
  for (const glm::dvec2& p : westBank) {
    if (p.y > south && p.y < north) strip.push_back(p);
  }
  strip.push_back(bankAt(north));
  strip.push_back({parkWest, north});
  strip.push_back({parkWest, south});
  g.areas.push_back(std::move(riverside));

  // Neighbourhoods: downtown at the centre, the others around it at 55 % of the way to the edge,
  // 4 to 8 of them as the city grows (one more per 1.5 km of its size beyond 1.5 km).
  const long count = std::clamp(static_cast<long>(span / 1500.0) + 3, 4L, 8L);
  const glm::dvec2 centre{0.5 * (west + east), 0.5 * (south + north)};
  g.places.push_back({GroundLabelKind::Neighbourhood, centre, "Downtown", 60});
  for (long k = 0; k + 1 < count; ++k) {
    const double angle = kPi / 2 + 2.0 * kPi * static_cast<double>(k) / static_cast<double>(count - 1);
    const glm::dvec2 at =
        centre + 0.55 * glm::dvec2{0.5 * (east - west) * std::cos(angle), 0.5 * (north - south) * std::sin(angle)};
    // The name of the compass direction nearest the angle (sectors of 45 degrees from east).
    const auto sector = static_cast<std::size_t>(std::lround(angle / (kPi / 4))) % 8;
    g.places.push_back({GroundLabelKind::Neighbourhood, at, kQuarterNames[sector], 80});
  }
  return g;
}

}  // namespace

SynthRandom::SynthRandom(std::uint64_t seed) {
  SplitMix64 seeder{seed};
  for (std::uint64_t& s : s_) s = seeder.next();
}

std::uint64_t SynthRandom::next() {
  const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = rotl(s_[3], 45);
  return result;
}

double SynthRandom::uniform() {
  return static_cast<double>(next() >> 11) * 0x1.0p-53;
}

double SynthRandom::uniform(double lo, double hi) {
  return lo + (hi - lo) * uniform();
}

double SynthRandom::normal() {
  const double u1 = std::max(uniform(), 1e-300);
  const double u2 = uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
}

CityModel generateSynthCity(const SynthCityOptions& options) {
  CityModel model;
  model.originLon = options.originLon;
  model.originLat = options.originLat;
  model.sources = {"synth-city --buildings " + std::to_string(options.buildings) + " --seed " +
                   std::to_string(options.seed)};
  model.buildings.reserve(static_cast<std::size_t>(options.buildings));
  SynthRandom rng(options.seed);

  // The tall core scales with the city: its radius holds about 4 % of the buildings.
  const double cityRadius = std::sqrt(static_cast<double>(options.buildings) / 12.0 * kPitchX * kPitchY / kPi);
  const double coreRadius = std::max(300.0, 0.2 * cityRadius);

  std::uint64_t made = 0;
  std::uint64_t blocks = 0;
  std::vector<std::pair<long, long>> parks;  // the blocks left empty
  for (std::uint64_t blockIndex = 0; made < options.buildings; ++blockIndex) {
    blocks = blockIndex + 1;
    long bi = 0, bj = 0;
    spiral(blockIndex, bi, bj);
    const double bx = static_cast<double>(bi) * kPitchX - kBlockWidth / 2;
    const double by = static_cast<double>(bj) * kPitchY - kBlockDepth / 2;
    const double blockCentreDistance = std::hypot(bx + kBlockWidth / 2, by + kBlockDepth / 2);
    const double coreness = std::exp(-std::pow(blockCentreDistance / coreRadius, 2.0));  // 1 in the core
    // A few blocks are parks (no buildings) outside the core.
    if (blockIndex > 0 && rng.chance(0.04 * (1.0 - coreness))) {
      parks.emplace_back(bi, bj);
      continue;
    }

    // Lots: two rows back to back, frontages 14–34 m (wider in the core).
    std::vector<Lot> lots;
    for (int row = 0; row < 2; ++row) {
      const double y0 = by + row * kBlockDepth / 2;
      double x = bx;
      while (x < bx + kBlockWidth - 8.0) {
        double w = rng.uniform(14.0, 24.0 + 10.0 * coreness);
        if (bx + kBlockWidth - (x + w) < 10.0) w = bx + kBlockWidth - x;
        lots.push_back({x, y0, x + w, y0 + kBlockDepth / 2});
        x += w;
      }
    }
    // Occasionally a whole half-block becomes one courtyard building.
    const bool courtyardBlock = rng.chance(0.06 + 0.06 * coreness);

    for (std::size_t li = 0; li < lots.size() && made < options.buildings; ++li) {
      Lot lot = lots[li];
      bool courtyard = false;
      if (courtyardBlock && li == 0) {
        // Merge the first row's lots into one.
        std::size_t last = li;
        while (last + 1 < lots.size() && lots[last + 1].y0 == lot.y0) ++last;
        lot.x1 = lots[last].x1;
        li = last;
        courtyard = true;
      }
      Building b;
      BuildingAttributes& a = b.attributes;
      a.id = "s" + std::to_string(made + 1);
      const double setback = rng.uniform(0.5, 3.0);
      const double x0 = lot.x0 + 0.6, x1 = lot.x1 - 0.6;
      const double y0 = lot.y0 + (lot.y0 > by ? 1.0 : setback);
      const double y1 = lot.y1 - (lot.y0 > by ? setback : 1.0);

      // Storeys: lognormal whose median falls from ~14 in the core to ~3 at the edge, plus a
      // heavy tail of towers in the core (docs/synth-city.md).
      const double median = 4.6 + 12.0 * coreness;
      double storeys = median * std::exp(0.5 * rng.normal());
      if (rng.chance(0.03 + 0.10 * coreness)) storeys *= rng.uniform(2.0, 6.0);
      const int s = std::clamp(static_cast<int>(std::lround(storeys)), 1, 110);

      // Use by place and size.
      const double u = rng.uniform();
      if (u < 0.004)
        a.use = "hospital";
      else if (u < 0.006)
        a.use = "fire_station";
      else if (u < 0.016)
        a.use = "school";
      else if (coreness > 0.5)
        a.use = u < 0.7 ? "office" : (u < 0.85 ? "retail" : "residential");
      else if (u < 0.06)
        a.use = "industrial";
      else if (u < 0.16)
        a.use = "retail";
      else if (u < 0.22 && s <= 2)
        a.use = "house";
      else
        a.use = "residential";
      if (a.use == "hospital")
        a.name = "Synthetic Hospital " + std::to_string(made + 1);
      else if (a.use == "school")
        a.name = "Synthetic School " + std::to_string(made + 1);
      else if (a.use == "fire_station")
        a.name = "Fire Station " + std::to_string(made + 1);
      a.amenity = a.use == "hospital" || a.use == "school" || a.use == "fire_station" ? a.use : "";
      // Addresses on the east-west streets: "1204 North 13th Street". Streets are numbered north and
      // south of the centre line; house numbers grow by 100 per block away from the centre.
      const long street = bj * 2 + (lot.y0 > by ? 1 : 0);
      const long number =
          std::labs(bi) * 100 + static_cast<long>(std::lround((lot.x0 - bx) / 4.0)) * 2 + (bi < 0 ? 1 : 2);
      a.address =
          std::to_string(number) + (street >= 0 ? " North " : " South ") + ordinal(std::labs(street) + 1) + " Street";

      const float storeyHeight = storeyHeightForUse(a.use);
      a.storeys = static_cast<std::uint16_t>(s);
      a.heightM = static_cast<float>(s) * storeyHeight * static_cast<float>(rng.uniform(0.97, 1.05));
      a.heightSource = ValueSource::Tagged;
      a.storeysSource = ValueSource::Tagged;
      // Older stock in the middle of the city, newer at its edge, then materials by era and size.
      const double year =
          std::clamp(1965.0 + 35.0 * (1.0 - coreness) * rng.uniform(-0.5, 1.5) + 28.0 * rng.normal(), 1850.0, 2024.0);
      a.startYear = static_cast<std::int16_t>(std::lround(year));
      if (a.use == "house" && rng.chance(0.7))
        a.material = "wood";
      else if (s <= 5 && a.startYear < 1935 && rng.chance(0.6))
        a.material = "brick";
      else if (s >= 8 && rng.chance(0.45))
        a.material = "steel";
      else if (s >= 4)
        a.material = "concrete";

      BuildingPart part;
      part.heightM = a.heightM;
      const double w = x1 - x0, d = y1 - y0;
      const double shape = rng.uniform();
      if (courtyard && w > 30.0 && d > 18.0) {
        addRect(part.points, x0, y0, x1, y1);
        const double m = std::min(w, d) * 0.28;
        // The courtyard, clockwise.
        part.points.insert(part.points.end(), {{x0 + m, y0 + m}, {x0 + m, y1 - m}, {x1 - m, y1 - m}, {x1 - m, y0 + m}});
        part.ringEnds = {4, 8};
      } else if (shape < 0.22 && w > 12.0 && d > 14.0) {
        // An L: the rectangle minus a corner notch at the back.
        const double nx = w * rng.uniform(0.35, 0.6), ny = d * rng.uniform(0.35, 0.6);
        const bool front = lot.y0 > by;  // the back of the lot faces the block's middle
        if (!front) {
          part.points = {{x0, y0}, {x1, y0}, {x1, y1 - ny}, {x1 - nx, y1 - ny}, {x1 - nx, y1}, {x0, y1}};
        } else {
          part.points = {{x0, y0}, {x1 - nx, y0}, {x1 - nx, y0 + ny}, {x1, y0 + ny}, {x1, y1}, {x0, y1}};
        }
        part.ringEnds = {6};
      } else {
        addRect(part.points, x0, y0, x1, y1);
        part.ringEnds = {4};
      }
      double area = 0.0;
      double cx = 0.0, cy = 0.0;
      std::uint32_t begin = 0;
      for (std::uint32_t end : part.ringEnds) {
        for (std::uint32_t i = begin; i < end; ++i) {
          const glm::dvec2 p = part.points[i];
          const glm::dvec2 q = part.points[i + 1 < end ? i + 1 : begin];
          const double c = p.x * q.y - q.x * p.y;
          area += c;
          cx += (p.x + q.x) * c;
          cy += (p.y + q.y) * c;
        }
        begin = end;
      }
      area *= 0.5;
      a.footprintAreaM2 = static_cast<float>(area);
      a.centroidX = cx / (6.0 * area);
      a.centroidY = cy / (6.0 * area);
      b.parts.push_back(std::move(part));
      inferSeismicAttributes(a, false);
      model.buildings.push_back(std::move(b));
      ++made;
    }
  }
  makeDetailedTowers(model, options.detailedTowers);
  if (options.ground) model.ground = synthGround(blocks, parks);
  return model;
}

}  // namespace qv::prep
