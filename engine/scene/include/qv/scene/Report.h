// The situation report: one print-ready HTML page for a mayor, a council or a press office, after
// USGS PAGER's one-page report and the Hazus summary report. The viewer (quakeview.report(), the
// panel's "Report") and `quakeview-prep report` make it from the same files with this one function,
// so the two documents are byte-identical for the same city (docs/report.md).
#pragma once

#include <span>
#include <string>

#include "qv/format/ResponseTile.h"
#include "qv/format/SearchIndex.h"
#include "qv/format/Tileset.h"
#include "qv/seismic/ConsequencesFile.h"

namespace qv {

/// What the report is made from: the city's manifest (its response, event and sources), the
/// consequence totals (consequences.json), the search index and the response summary in its order
/// (index.qvs; its LOSS section: each building's probabilities for the map and the facilities).
/// The spans may be empty and the pointers null (a city without them): the report then says which
/// part is missing instead of showing numbers.
struct ReportInputs {
  const Tileset* tileset = nullptr;
  const seismic::ConsequenceTotals* consequences = nullptr;
  std::span<const SearchEntry> buildings;
  const ResponseSummaryTile* summary = nullptr;  ///< aligned with `buildings`
};

/// The impact level on PAGER's published alert thresholds (Wald et al. 2010, USGS Fact Sheet
/// 2010-3036): fatalities green 0, yellow 1-99, orange 100-999, red 1,000 or more; economic losses
/// green under 1 million USD, yellow up to 100 million, orange up to 1 billion, red above. Applied
/// to the city's expected deaths (rounded) and repair cost; the level is the higher of the two.
enum class ImpactLevel { Green, Yellow, Orange, Red };
ImpactLevel fatalityLevel(double expectedDeaths);
ImpactLevel economicLevel(double repairCostUsd);
std::string_view impactLevelName(ImpactLevel level);  ///< "green", "yellow", "orange", "red"

/// The report as a complete HTML document (UTF-8, styles inline, no scripts, nothing fetched): the
/// event, the headline numbers with 90 % intervals and the impact level, a map of the city coloured
/// by the probability of moderate damage or worse (SVG, with legend, scale bar and north arrow), the
/// tables (damage by occupancy class and by structural type, essential facilities with their damage
/// and functionality on day one, casualties at 2 AM, 2 PM and 5 PM, districts), what the results
/// rest on and their limits, the sources and licences, and the provenance line every export
/// carries. Its content lies in one <div class="qv-report">, its styles scoped to it, so that a
/// page can embed it (the viewer prints it in place of the canvas). Deterministic: no clock.
std::string situationReportHtml(const ReportInputs& inputs);

}  // namespace qv
