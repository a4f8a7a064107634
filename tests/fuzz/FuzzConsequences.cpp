// fuzz_consequences: arbitrary text into parseConsequences (the viewer reads consequences.json from
// any server). What parses must write and parse again to the same shape, and the situation report
// made from it must be a whole document: nothing a file holds (NaN, huge counts, names with markup
// or control characters) may crash it, break its markup or run as script.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "FuzzSupport.h"
#include "qv/core/Text.h"
#include "qv/scene/Report.h"
#include "qv/seismic/ConsequencesFile.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace qv;
  constexpr std::string_view kName = "https://example.org/city/response-1/consequences.json";
  const std::string_view json(reinterpret_cast<const char*>(data), size);
  const Result<seismic::ConsequenceTotals> parsed = seismic::parseConsequences(json, std::string(kName));
  fuzz::checkErrorNamesInput(parsed, kName);
  if (!parsed.ok()) return 0;
  const Result<seismic::ConsequenceTotals> again =
      seismic::parseConsequences(seismic::consequencesToJson(*parsed), std::string(kName));
  fuzz::check(again.ok(), "a written consequences file does not parse");
  fuzz::check(again->districts.size() == parsed->districts.size(), "districts lost on writing");
  fuzz::check(again->byOccupancy.size() == parsed->byOccupancy.size(), "class rows lost on writing");
  fuzz::check(again->city.byTime.has_value() == parsed->city.byTime.has_value(), "casualties by time lost");

  Tileset tileset;
  tileset.name = "fuzz";
  tileset.response = ResponseInfo{};
  tileset.response->eventType = "SCENARIO";
  tileset.response->timeOfDay = parsed->timeOfDay;
  ReportInputs inputs;
  inputs.tileset = &tileset;
  inputs.consequences = &*parsed;
  const std::string html = situationReportHtml(inputs);
  fuzz::check(html.rfind("<!DOCTYPE html>", 0) == 0, "the report does not start as a document");
  fuzz::check(html.size() > 16 && html.substr(html.size() - 16) == "</body>\n</html>\n", "the report is not whole");
  fuzz::check(html.find("<script") == std::string::npos, "the report carries a script");
  fuzz::check(isValidUtf8(html), "the report is not valid UTF-8");
  return 0;
}
