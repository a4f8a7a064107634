// Readers for acceleration records: PEER AT2 (the NGA layout and the older layouts), one value a
// line with a given time step, and two columns (time, acceleration). Bad input never throws: the
// Result's message names the file and the 1-based line ("elCentro.AT2:7: ...").
//
// Layouts recognised (docs/seismic.md lists examples):
//   - header lines of text, one of which gives the point count and step:
//       "NPTS=  4096, DT=   .0100 SEC" (NGA),  "NPTS= 1559, DT= .02000 SEC",
//       "  3000    .0100    NPTS, DT" (pre-NGA PEER),  "1559 points at equal spacing of 0.02 sec";
//     then values in reading order, any count a line (8F10.5, 5E15.7, ...). Fortran fields that run
//     together ("0.123-0.456") and D exponents ("1.0D-03") are accepted.
//   - a one-line numeric header "NPTS DT" (an integer count and a step) followed by exactly that many
//     values.
//   - no header, one value a line (or several): the step must come from the caller.
//   - no header, two values on every line, the first strictly increasing: time and acceleration;
//     the step is the time difference, checked uniform.
// Units come from the header ("UNITS OF G.", "(g)", "in g", "cm/s/s", "CM/SEC**2", "gal", "m/s2";
// punctuation and case do not matter, docs/seismic.md) or from the caller; a header and a caller
// that disagree is an error, as is neither giving units.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "qv/core/Result.h"
#include "qv/seismic/GroundMotion.h"

namespace qv::seismic {

enum class GroundMotionFormat { Auto, PeerAt2, ValuesOnly, TimeAcceleration };

struct GroundMotionReadOptions {
  GroundMotionFormat format = GroundMotionFormat::Auto;
  std::optional<AccelerationUnit> units;  ///< required when the file does not say
  std::optional<double> timeStepS;        ///< required when the file has no step (checked otherwise)
};

/// What a reader found besides the samples (for messages and the mdof command's report).
struct GroundMotionSource {
  GroundMotionFormat format = GroundMotionFormat::Auto;  ///< the layout detected
  AccelerationUnit units = AccelerationUnit::G;          ///< the units applied
  bool unitsFromFile = false;
  bool timeStepFromFile = false;
};

/// Parses `text`; `name` is used in messages (normally the file name).
Result<GroundMotion> parseGroundMotion(std::string_view text, std::string_view name,
                                       const GroundMotionReadOptions& options = {},
                                       GroundMotionSource* source = nullptr);

/// Reads and parses a file (at most 256 MiB). The motion's name is the file name without folders.
Result<GroundMotion> readGroundMotionFile(const std::string& path, const GroundMotionReadOptions& options = {},
                                          GroundMotionSource* source = nullptr);

/// "PEER AT2", "values", "time-acceleration".
std::string_view groundMotionFormatName(GroundMotionFormat format);

}  // namespace qv::seismic
