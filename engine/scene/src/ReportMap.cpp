#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "ReportParts.h"
#include "qv/format/FacilityCategory.h"
#include "qv/geometry/GeoFrame.h"

namespace qv::report {
namespace {

struct Building {
  float x = 0, y = 0;
  double atLeastModerate = -1;  ///< P(DS >= moderate), -1 without probabilities
};

/// The map's classes of P(moderate or worse): under 1 %, 1-5, 5-10, 10-25, 25-50, 50 % or more.
constexpr double kMapClasses[5] = {0.01, 0.05, 0.10, 0.25, 0.50};
int mapClass(double p) {
  int k = 0;
  while (k < 5 && p >= kMapClasses[k]) ++k;
  return k;
}
/// The colour of class k: the viewer's damage ramp at k / 5.
std::string classColor(int k) {
  return hexColor(paletteRamp(static_cast<float>(k) / 5.0f));
}

/// A length for the scale bar: 1, 2 or 5 times a power of ten, about a quarter of `span` metres.
double niceLength(double span) {
  const double target = span / 4;
  const double power = std::pow(10.0, std::floor(std::log10(std::max(target, 1.0))));
  for (const double m : {5.0, 2.0, 1.0}) {
    if (m * power <= target) return m * power;
  }
  return power;
}

std::string lengthLabel(double metres) {
  return metres >= 1000 ? fmt("%g km", metres / 1000) : fmt("%g m", metres);
}

}  // namespace

void writeMap(std::string& out, const ReportInputs& in) {
  std::vector<Building> buildings;
  buildings.reserve(in.buildings.size());
  float minX = 0, maxX = 0, minY = 0, maxY = 0;
  for (std::size_t i = 0; i < in.buildings.size(); ++i) {
    const SearchEntry& e = in.buildings[i];
    Building b{e.x, e.y, -1};
    if (const auto p = structuralOf(in.summary, i)) b.atLeastModerate = (*p)[2] + (*p)[3] + (*p)[4];
    if (buildings.empty()) {
      minX = maxX = b.x;
      minY = maxY = b.y;
    }
    minX = std::min(minX, b.x);
    maxX = std::max(maxX, b.x);
    minY = std::min(minY, b.y);
    maxY = std::max(maxY, b.y);
    buildings.push_back(b);
  }
  out += "<h2 class=\"page\">Map: where the damage is</h2>\n";
  if (buildings.empty()) {
    out += "<p>No map: the city has no search index (its buildings' positions).</p>\n";
    return;
  }
  // Cells of the same size in both directions, about 150 along the longer side of the city.
  const double spanX = std::max(1.0, static_cast<double>(maxX - minX));
  const double spanY = std::max(1.0, static_cast<double>(maxY - minY));
  const double cell = std::max(spanX, spanY) / 150.0;
  const int cols = std::max(1, static_cast<int>(std::ceil(spanX / cell)) + 1);
  const int rows = std::max(1, static_cast<int>(std::ceil(spanY / cell)) + 1);
  std::vector<double> sum(static_cast<std::size_t>(cols * rows), 0.0);
  std::vector<int> counted(sum.size(), 0), present(sum.size(), 0);
  for (const Building& b : buildings) {
    const int cx = std::clamp(static_cast<int>((b.x - minX) / cell), 0, cols - 1);
    const int cy = std::clamp(static_cast<int>((b.y - minY) / cell), 0, rows - 1);
    const auto at = static_cast<std::size_t>(cy * cols + cx);
    ++present[at];
    if (b.atLeastModerate >= 0) {
      sum[at] += b.atLeastModerate;
      ++counted[at];
    }
  }
  // A cell's colour: the class of its buildings' mean probability (kMapClasses), so that a moderate
  // earthquake's few percent show as well as a strong one's tens of percent.
  const auto cellColor = [&](std::size_t at) {
    if (counted[at] == 0) return hexColor(kNoResultColor);
    return classColor(mapClass(sum[at] / counted[at]));
  };
  // The picture: 1000 units wide at most (the figure scales to the page), north up.
  // Whole units a cell, so that the path data below stays integers.
  const double unit = std::max(1, 1000 / std::max(cols, rows));
  const double width = cols * unit, height = rows * unit;
  const double margin = 40;
  const double viewWidth = width + 2 * margin, viewHeight = height + 2 * margin + 40;
  out += fmt("<div class=\"map\"><svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" ", viewWidth) +
         fmt("height=\"%.0f\" ", viewHeight) + fmt("viewBox=\"0 0 %.0f ", viewWidth) +
         fmt("%.0f\" role=\"img\" aria-label=\"Map of the city coloured by the probability of moderate damage or "
             "worse\">\n",
             viewHeight);
  out +=
      fmt("<rect x=\"0\" y=\"0\" width=\"%.0f\" ", viewWidth) + fmt("height=\"%.0f\" fill=\"#ffffff\"/>", viewHeight);
  out += fmt("<rect x=\"%.0f\" ", margin) + fmt("y=\"%.0f\" ", margin) + fmt("width=\"%.1f\" ", width) +
         fmt("height=\"%.1f\" fill=\"#aebbc4\"/>\n", height);
  // One path per colour, a rectangle per run of equal cells in a row ("M x y h w v u h -w z"):
  // a few hundred kilobytes less than an element per cell for 100,000 buildings.
  std::map<std::string, std::string> paths;
  for (int y = 0; y < rows; ++y) {
    int x = 0;
    while (x < cols) {
      const auto at = static_cast<std::size_t>(y * cols + x);
      if (present[at] == 0) {
        ++x;
        continue;
      }
      const std::string color = cellColor(at);
      int end = x + 1;
      while (end < cols) {
        const auto next = static_cast<std::size_t>(y * cols + end);
        if (present[next] == 0) break;
        if (cellColor(next) != color) break;
        ++end;
      }
      // Row y counts from the south; the picture's rows from the top.
      const int u = static_cast<int>(unit);
      const int runWidth = (end - x) * u;
      std::string& d = paths[color];
      d += "M" + std::to_string(static_cast<int>(margin) + x * u) + " " +
           std::to_string(static_cast<int>(margin) + (rows - 1 - y) * u) + "h" + std::to_string(runWidth) + "v" +
           std::to_string(u) + "h-" + std::to_string(runWidth) + "z";
      x = end;
    }
  }
  out += "<g shape-rendering=\"crispEdges\">\n";
  for (const auto& [color, d] : paths) out += "<path fill=\"" + color + "\" d=\"" + d + "\"/>\n";
  out += "</g>\n";
  // District outlines and names (where the response kept them), clipped to the map.
  if (in.consequences != nullptr && in.tileset != nullptr) {
    const GeoFrame geo(in.tileset->originLon, in.tileset->originLat);
    const auto toMap = [&](const std::array<double, 2>& lonLat, double& px, double& py) {
      const auto m = geo.forward(LonLat{lonLat[0], lonLat[1]});
      if (!m) return false;
      px = margin + (m->x - minX) / cell * unit;
      py = margin + (rows - (m->y - minY) / cell) * unit;
      return true;
    };
    std::string lines, labels;
    std::size_t named = 0;
    for (const auto& district : in.consequences->districts) {
      double sumX = 0, sumY = 0, weight = 0;
      for (const auto& ring : district.outline) {
        std::string d;
        for (const auto& point : ring) {
          double px = 0, py = 0;
          if (!toMap(point, px, py)) continue;
          d += (d.empty() ? "M" : "L") + fmt("%.1f", px) + " " + fmt("%.1f", py);
          sumX += px;
          sumY += py;
          weight += 1;
        }
        if (!d.empty()) lines += "<path d=\"" + d + "Z\"/>\n";
      }
      // The name at the middle of its outline's points, for the first 40 districts.
      if (weight > 0 && named < 40) {
        ++named;
        labels += fmt("<text x=\"%.1f\" ", sumX / weight) + fmt("y=\"%.1f\">", sumY / weight) + esc(district.name) +
                  "</text>\n";
      }
    }
    if (!lines.empty()) {
      out += fmt("<clipPath id=\"qv-report-map-clip\"><rect x=\"%.0f\" ", margin) + fmt("y=\"%.0f\" ", margin) +
             fmt("width=\"%.1f\" ", width) + fmt("height=\"%.1f\"/></clipPath>\n", height);
      out += "<g clip-path=\"url(#qv-report-map-clip)\" fill=\"none\" stroke=\"#1d3557\" stroke-width=\"2\">\n" +
             lines + "</g>\n";
      out +=
          "<g clip-path=\"url(#qv-report-map-clip)\" font-family=\"sans-serif\" font-size=\"15\" "
          "font-weight=\"bold\" fill=\"#1d3557\" stroke=\"#ffffff\" stroke-width=\"3\" paint-order=\"stroke\" "
          "text-anchor=\"middle\">\n" +
          labels + "</g>\n";
    }
  }
  // Essential facilities: small black-edged circles.
  for (std::size_t i = 0; i < in.buildings.size(); ++i) {
    if (in.buildings[i].facility != FacilityCategory::Essential) continue;
    const double px = margin + (in.buildings[i].x - minX) / cell * unit;
    const double py = margin + (rows - (in.buildings[i].y - minY) / cell) * unit;
    out += fmt("<circle cx=\"%.1f\" ", px) + fmt("cy=\"%.1f\" r=\"3.5\" fill=\"none\" ", py) +
           "stroke=\"#000\" stroke-width=\"1\"/>\n";
  }
  // North arrow (the city frame's y axis points to true north at its origin).
  out += fmt("<g transform=\"translate(%.0f,", width + 2 * margin - 28) +
         fmt("%.0f)\"><path d=\"M0,-18 L8,6 L0,1 L-8,6 Z\" fill=\"#222\"/>", margin + 22) +
         "<text x=\"0\" y=\"22\" font-size=\"16\" text-anchor=\"middle\" font-family=\"sans-serif\">N</text></g>\n";
  // Scale bar.
  const double metres = niceLength(spanX);
  const double barUnits = metres / cell * unit;
  const double barY = height + 2 * margin + 8;
  out += fmt("<g font-family=\"sans-serif\" font-size=\"16\"><rect x=\"%.1f\" ", margin) + fmt("y=\"%.1f\" ", barY) +
         fmt("width=\"%.1f\" height=\"6\" fill=\"#222\"/>", barUnits) +
         fmt("<text x=\"%.1f\" ", margin + barUnits + 8) + fmt("y=\"%.1f\">", barY + 7) + lengthLabel(metres) +
         "</text></g>\n";
  out += "</svg></div>\n";
  // Legend.
  out +=
      "<p class=\"small\">Colour: the mean probability of moderate structural damage or worse (HAZUS 5.1) of the "
      "buildings in each square of " +
      lengthLabel(std::round(cell)) + ": ";
  bool hasOutlines = false;
  if (in.consequences != nullptr) {
    for (const auto& d : in.consequences->districts) hasOutlines = hasOutlines || !d.outline.empty();
  }
  // Swatches as small SVG pictures (presentation attributes, not style attributes: a page whose
  // Content Security Policy forbids inline styles embeds the report as it is).
  const auto swatch = [](const std::string& color) {
    return "<svg class=\"swatch\" width=\"14\" height=\"10\" viewBox=\"0 0 14 10\"><rect x=\"0.5\" y=\"0.5\" "
           "width=\"13\" height=\"9\" fill=\"" +
           color + "\" stroke=\"#666\"/></svg>";
  };
  const char* labels[6] = {"under 1 %",     "1&ndash;5 %",   "5&ndash;10 %",
                           "10&ndash;25 %", "25&ndash;50 %", "50 % or more"};
  for (int k = 0; k < 6; ++k) out += swatch(classColor(k)) + " " + labels[k] + "; ";
  out += swatch(hexColor(kNoResultColor)) + " no result; " + swatch("#aebbc4") +
         " no buildings. Circles: essential facilities (hospitals, fire and police stations). " +
         std::string(hasOutlines ? "Blue lines: the districts of the table below."
                                 : "No district outlines: the response keeps none (made without districts, or "
                                   "before outlines were kept).") +
         "</p>\n";
}

}  // namespace qv::report
