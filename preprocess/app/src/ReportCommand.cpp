// `quakeview-prep report DIR [--out FILE.html]`: the situation report of a city's response, the same
// document as the viewer's "Report" (qv::situationReportHtml over the same files).
#include <cstdio>
#include <optional>

#include "CityFiles.h"
#include "Commands.h"
#include "qv/format/SearchIndex.h"
#include "qv/prep/Cli.h"
#include "qv/prep/Files.h"
#include "qv/scene/Export.h"
#include "qv/scene/Report.h"

namespace qv::prep {
namespace {

const char* const kUsage =
    "usage: quakeview-prep report DIR [--out FILE.html]\n"
    "  Writes the situation report of the city's earthquake response: one print-ready HTML page\n"
    "  (A4 or Letter) with the event (SCENARIO or ACTUAL), the headline numbers and their 90 %\n"
    "  intervals, an impact level on PAGER's thresholds, a map coloured by damage, damage by\n"
    "  occupancy class and building type, essential facilities, casualties at 2 AM, 2 PM and 5 PM,\n"
    "  districts, what the results rest on and the sources. The viewer's \"Report\" gives the same\n"
    "  document for the same city.\n"
    "  --out FILE.html  where to write it (replaced whole, never half-written); '-' prints it.\n"
    "                   Default: quakeview-<city>-<event>-report.html in the current directory,\n"
    "                   the name the viewer downloads it under.\n";

}  // namespace

int runReport(const CommandArgs& argv) {
  std::string error;
  const auto args = Args::parse(argv, {{"out"}, {"help", false}}, error);
  if (!args || args->has("help")) {
    if (!args) std::fprintf(stderr, "report: %s\n", error.c_str());
    std::fputs(kUsage, args ? stdout : stderr);
    return args ? kExitOk : kExitUsage;
  }
  if (args->positional().size() != 1) {
    std::fprintf(stderr, "report: give exactly one city directory\n%s", kUsage);
    return kExitUsage;
  }
  const std::string dir = args->positional()[0];
  const auto tileset = loadTileset(dir);
  if (!tileset.ok()) {
    std::fprintf(stderr, "report: %s\n", tileset.error().c_str());
    return kExitDataError;
  }
  const Tileset& t = *tileset;
  if (!t.response) {
    std::fprintf(stderr, "report: %s has no earthquake response; run `quakeview-prep response --city %s ...` first\n",
                 dir.c_str(), dir.c_str());
    return kExitDataError;
  }
  const auto fail = [](const std::string& message) {
    std::fprintf(stderr, "report: %s\n", message.c_str());
    return kExitDataError;
  };
  // The same files the viewer reads: the consequence totals, the search index and the response
  // summary in its order (not for a response older than the buildings: its index positions no
  // longer match, as the viewer also ignores it).
  std::optional<seismic::ConsequenceTotals> consequences;
  if (t.response->consequences) {
    auto bytes = loadCityFile(dir, *t.response->consequences);
    if (!bytes.ok()) return fail(bytes.error());
    auto parsed =
        seismic::parseConsequences(std::string_view(reinterpret_cast<const char*>(bytes->data()), bytes->size()),
                                   dir + "/" + t.response->consequences->file);
    if (!parsed.ok()) return fail(parsed.error());
    consequences = std::move(parsed).value();
  }
  std::vector<SearchEntry> entries;
  std::optional<ResponseSummaryTile> summary;
  if (t.search) {
    auto bytes = loadCityFile(dir, *t.search);
    if (!bytes.ok()) return fail(bytes.error());
    auto decoded = decodeSearchIndex(*bytes, dir + "/" + t.search->file);
    if (!decoded.ok()) return fail(decoded.error());
    entries = std::move(decoded).value();
    if (t.response->summaryIndex && !t.responseOutOfDate()) {
      auto summaryBytes = loadCityFile(dir, *t.response->summaryIndex);
      if (!summaryBytes.ok()) return fail(summaryBytes.error());
      const std::string path = dir + "/" + t.response->summaryIndex->file;
      auto all = decodeResponseSummary(*summaryBytes, path);
      if (!all.ok()) return fail(all.error());
      if (all->buildings.size() != entries.size()) {
        return fail(path + ": " + std::to_string(all->buildings.size()) + " buildings, the search index has " +
                    std::to_string(entries.size()));
      }
      summary = std::move(all).value();
    }
  }
  ReportInputs inputs;
  inputs.tileset = &t;
  inputs.consequences = consequences ? &*consequences : nullptr;
  inputs.buildings = entries;
  inputs.summary = summary ? &*summary : nullptr;
  const std::string html = situationReportHtml(inputs);

  const std::string out = args->value("out").value_or(exportFileName(t, {}, "report", "html"));
  if (out == "-") {
    std::fwrite(html.data(), 1, html.size(), stdout);
    return kExitOk;
  }
  if (Status s = writeFileAtomic(out, html); !s.ok()) return fail(s.error());
  std::printf("wrote %s (%zu KB)\n", out.c_str(), (html.size() + 1023) / 1024);
  return kExitOk;
}

}  // namespace qv::prep
