// Where a JSON text is broken: simdjson says that a document is malformed but not where, so on a
// parse error the text is run through this small RFC 8259 checker (UTF-8 included) to find the
// first offending byte, reported as line:column. Shared by the GeoJSON (prep::ingest) and CityJSON
// (prep::lod2) readers.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace qv::prep {

struct JsonSyntaxProblem {
  std::size_t offset = 0;  ///< byte offset of the first offending byte
  std::string what;        ///< "unexpected '}', expected a value", "invalid UTF-8", ...
};

/// The first syntax error of `text`, or nullopt when it is well-formed JSON.
std::optional<JsonSyntaxProblem> findJsonSyntaxProblem(std::string_view text);

/// "line:column" (both from 1, columns in bytes) of a byte offset.
std::string lineColumn(std::string_view text, std::size_t offset);

}  // namespace qv::prep
