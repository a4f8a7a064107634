// Small OSM cities written by the response command tests, and reading back what the tool wrote.
#pragma once

#include <fstream>
#include <iterator>
#include <string>

namespace qv::test {

inline std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// A square footprint of side ~20 m at (lon, lat) as an OSM way with `tags`.
inline std::string square(int id, double lon, double lat, const std::string& tags) {
  const double d = 0.0002;
  std::string s;
  const double corners[4][2] = {{lon, lat}, {lon + d, lat}, {lon + d, lat + d}, {lon, lat + d}};
  for (int k = 0; k < 4; ++k) {
    s += "<node id=\"" + std::to_string(id * 10 + k) + "\" lat=\"" + std::to_string(corners[k][1]) + "\" lon=\"" +
         std::to_string(corners[k][0]) + "\"/>\n";
  }
  s += "<way id=\"" + std::to_string(id) + "\">";
  for (int k = 0; k <= 4; ++k) s += "<nd ref=\"" + std::to_string(id * 10 + k % 4) + "\"/>";
  return s + tags + "</way>\n";
}

inline std::string tag(const std::string& k, const std::string& v) {
  return "<tag k=\"" + k + "\" v=\"" + v + "\"/>";
}

}  // namespace qv::test
