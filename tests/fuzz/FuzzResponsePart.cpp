// fuzz_response_part: arbitrary bytes into decodePartResults (a sharded run's results.qvp, read by
// the merge from a shared file system that may hold anything: a part cut short by a dying node, a
// file of another tool) and arbitrary text into parseCatalogue (a scenario catalogue). A results
// file that decodes must encode to the same bytes; a catalogue that parses gives scenarios with
// clean names and option arguments only; errors name the file.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "FuzzSupport.h"
#include "qv/prep/ResponseCatalogue.h"
#include "qv/prep/ResponseParts.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace qv;
  constexpr std::string_view kName = "/shared/city/staging/part-2-of-4/results.qvp";
  const auto decoded = prep::decodePartResults(std::span(data, size), kName);
  fuzz::checkErrorNamesInput(decoded, kName);
  if (decoded.ok()) {
    const auto encoded = prep::encodePartResults(*decoded);
    fuzz::check(encoded.size() == size && std::equal(encoded.begin(), encoded.end(), data),
                "a results file that decodes does not encode to the same bytes");
  }
  const std::string catalogueName = "/shared/catalogue.json";
  const auto catalogue =
      prep::parseCatalogue(std::string_view(reinterpret_cast<const char*>(data), size), "/shared", catalogueName);
  fuzz::checkErrorNamesInput(catalogue, catalogueName);
  if (catalogue.ok()) {
    fuzz::check(!catalogue->scenarios.empty() && catalogue->scenarios.size() <= prep::kMaxScenarios,
                "a catalogue without scenarios or with too many parsed");
    for (const prep::CatalogueScenario& s : catalogue->scenarios) {
      fuzz::check(!s.name.empty() && s.name.size() <= 200, "a scenario name out of bounds");
      for (const char c : s.name)
        fuzz::check(static_cast<unsigned char>(c) >= 0x20 && c != 0x7f, "a control character in a name");
      fuzz::check(s.args.empty() || s.args.front().rfind("--", 0) == 0,
                  "a scenario's arguments do not start with an option");
      for (const std::string& a : s.args) {
        if (a == "--city" || a == "--shard" || a == "--merge" || a == "--catalogue" || a == "--threads") {
          fuzz::contractBroken("a catalogue set an option it may not", a);
        }
      }
    }
  }
  return 0;
}
