// The embedded default city: a deterministic, realistic synthetic city generated from a seed, so
// the demo needs no data on the user's machine. See docs/synth-city.md for the layout, the shape
// mix and the storey distribution.
#pragma once

#include <cstdint>

#include "qv/prep/CityModel.h"

namespace qv::prep {

struct SynthCityOptions {
  std::uint64_t buildings = 100000;  ///< exactly this many (1 .. 10,000,000)
  std::uint64_t seed = 1;
  double originLon = -74.00;  ///< where the city's centre is placed (degrees)
  double originLat = 40.71;
  /// The tallest this-many rectangular or L-shaped buildings (of at least kMinTowerStoreys) become
  /// towers with setbacks: a podium over the footprint, a shaft and a crown over its main rectangle, each a part
  /// (BuildingPart::sourceId "<id>/podium",
  /// "<id>/shaft", "<id>/crown") on floor levels, for quakeview-prep to make LOD2 models of. 0: none.
  std::uint64_t detailedTowers = 0;
  /// The city's map in CityModel::ground (docs/synth-city.md "Map"): its avenues and streets
  /// (named), the empty blocks as parks, a river with a riverside park beyond its east edge and
  /// neighbourhood names. It takes no random numbers: the buildings are the same either way.
  bool ground = true;
};

inline constexpr std::uint16_t kMinTowerStoreys = 3;

/// Generates the city: buildings s1..sN on a street grid around (0, 0), growing outwards block by
/// block; the same options give the same city on every machine.
CityModel generateSynthCity(const SynthCityOptions& options);

/// A small, fast, fully specified PRNG (xoshiro256** seeded by SplitMix64, Blackman & Vigna 2018),
/// so results do not depend on the standard library's distributions.
class SynthRandom {
 public:
  explicit SynthRandom(std::uint64_t seed);
  std::uint64_t next();
  double uniform();                      ///< [0, 1)
  double uniform(double lo, double hi);  ///< [lo, hi)
  double normal();                       ///< standard normal (Box–Muller)
  bool chance(double p) { return uniform() < p; }

 private:
  std::uint64_t s_[4];
};

}  // namespace qv::prep
