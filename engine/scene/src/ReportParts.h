// Internal to the situation report (Report.cpp, ReportFormat.cpp, ReportMap.cpp): the text
// formatting its parts share and the map. Not part of engine::scene's interface.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "qv/scene/Palette.h"
#include "qv/scene/Report.h"

namespace qv::report {

/// HTML text: &, <, >, " escaped, invalid UTF-8 replaced, control characters (but tab and newline)
/// as spaces.
std::string esc(std::string_view raw);
/// printf of one number into a string of any length.
std::string fmt(const char* format, double value);
/// Whole numbers with thousands separators ("12,345"); "n/a" when not finite, %.3g from 1e15.
std::string grouped(double value);
/// An expected count of buildings or people: one decimal under 10, whole numbers above.
std::string count(double value);
/// "$16.49 bn", "$399.0 M", "$518 k", "$12".
std::string money(double usd);
/// "12 %", "4.5 %", "&lt;0.1 %".
std::string percent(double p);
/// "low &ndash; high" of an estimate (money or counts); "not computed" without bounds.
std::string range(const seismic::Estimate& e, bool isMoney = false);
/// "#rrggbb".
std::string hexColor(Rgb c);
/// P(structural DS = k), k 0..4, of the building at `i` of the summary (LOSS, else DPRB);
/// nullopt without probabilities or a result.
std::optional<std::array<double, 5>> structuralOf(const ResponseSummaryTile* summary, std::size_t i);

/// The map section: cells coloured by classes of P(moderate or worse), essential facilities,
/// district outlines and names, scale bar, north arrow and the colour key.
void writeMap(std::string& out, const ReportInputs& in);

}  // namespace qv::report
