// What the inspection window shows of a building's response, as text and scales: displacements in
// units that show them, drift ratios as percentages, round axis ticks for plots, the fixed scale of
// the per-storey drift bars and the error bound of the plotted (compressed) history. Pure: the UI
// layer draws with these; native tests pin them.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace qv {

/// A unit for displaying lengths: a value in this unit is metres / metresPerUnit.
struct DisplayUnit {
  const char* name = "m";  ///< "mm", "m", "in", "ft"
  double metresPerUnit = 1.0;
};

/// The unit a displacement of `metres` (its magnitude) is shown in: millimetres below 1 m, metres
/// from 1 m; with `feet`, inches below 1 ft, feet from 1 ft. Non-finite values: metres (feet).
DisplayUnit displacementUnit(double metres, bool feet = false);

/// A displacement (metres) as text with a unit that shows it: 0.020 -> "20 mm", 0.0004 -> "0.4 mm",
/// 0.0095 -> "9.5 mm", 1.23 -> "1.23 m"; below 10 mm one decimal, below 1 m whole millimetres, from
/// 1 m two decimals (a value that rounds up to the next unit is shown in it: 0.9996 -> "1.00 m").
/// With `feet`: 0.020 -> "0.79 in" (two decimals below 1 in, one below 1 ft), 1.23 -> "4.04 ft".
/// "0 mm" for 0; non-finite values give "-".
std::string displacementText(double metres, bool feet = false);

/// A drift ratio as a percentage: two decimals from 0.1 % ("0.22 %", "1.45 %"), three below
/// ("0.040 %"), so small drifts do not read as zero. Non-finite: "-".
std::string driftPercentText(double ratio);

/// Round tick values (1, 2 or 5 x 10^k apart) inside [low, high], at most `maxTicks` + 1 of them,
/// ascending; empty when the range is empty, not finite or maxTicks < 1. Ticks at the ends are
/// included when they fall on the step (0 is always a tick when inside the range).
std::vector<double> axisTicks(double low, double high, int maxTicks);

/// A tick's label: the value with as many decimals as the tick step needs ("0", "2.5", "0.25").
std::string tickLabel(double value, double step);

/// The fixed scale of the per-storey peak drift bars: from 0 to max(2.5 %, the complete-damage
/// threshold) so the bars of every building compare on one scale and the four HAZUS thresholds
/// (slight, moderate, extensive, complete; ratios, ascending) are on it. Rounded up to 0.5 %.
double storeyDriftScaleMax(const std::array<double, 4>& thresholds);

/// The largest error of a reconstructed floor displacement in the compressed history, as a
/// fraction of the building's peak roof displacement (docs/formats.md, "Quantization and error
/// bound": the encoder refines until every floor at every output frame is within it).
inline constexpr double kHistoryRelativeErrorBound = 0.019;

/// The bound on the error of an inter-storey drift ratio read from the compressed history: two
/// floors each within kHistoryRelativeErrorBound x peak roof displacement, over the storey height.
/// 0 for a non-positive storey height.
double historyDriftErrorBound(double peakRoofDisplacementM, double storeyHeightM);

}  // namespace qv
