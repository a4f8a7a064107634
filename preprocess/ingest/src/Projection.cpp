#include "qv/prep/Projection.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <thread>

namespace qv::prep {

bool validLonLat(double lon, double lat) {
  return std::isfinite(lon) && std::isfinite(lat) && std::abs(lat) <= 90.0 && std::abs(lon) <= 180.0;
}

CityProjection::CityProjection(double originLon, double originLat) : frame_(originLon, originLat) {
  assert(validLonLat(originLon, originLat) && std::abs(originLat) < 90.0);
}

std::array<double, 2> CityProjection::reverse(glm::dvec2 xy) const {
  const LonLat p = frame_.reverseUnchecked(xy);
  return {p.lon, p.lat};
}

std::optional<ProjectionGrid> ProjectionGrid::make(const CityProjection& projection, double minLon, double minLat,
                                                   double maxLon, double maxLat, std::size_t maxNodes,
                                                   unsigned threads) {
  if (!validLonLat(minLon, minLat) || !validLonLat(maxLon, maxLat) || !(minLon <= maxLon) || !(minLat <= maxLat))
    return std::nullopt;
  const double h = kStepDegrees;
  // One cell of margin on every side: points on the box's edges interpolate inside the grid.
  const double columns = std::floor((maxLon - minLon) / h) + 3.0;
  const double rows = std::floor((maxLat - minLat) / h) + 3.0;
  if (columns * rows > static_cast<double>(maxNodes)) return std::nullopt;
  ProjectionGrid grid;
  grid.lon0_ = minLon - h;
  grid.lat0_ = minLat - h;
  grid.columns_ = static_cast<int>(columns);
  grid.rows_ = static_cast<int>(rows);
  if (std::abs(grid.lat0_ + (rows - 1.0) * h) >= 90.0 || std::abs(grid.lat0_) >= 90.0) return std::nullopt;
  grid.nodes_.resize(static_cast<std::size_t>(grid.columns_) * static_cast<std::size_t>(grid.rows_));
  auto fillRows = [&](int firstRow, int endRow) {
    for (int j = firstRow; j < endRow; ++j) {
      for (int i = 0; i < grid.columns_; ++i) {
        grid.nodes_[static_cast<std::size_t>(j) * static_cast<std::size_t>(grid.columns_) +
                    static_cast<std::size_t>(i)] = projection.forward(grid.lon0_ + i * h, grid.lat0_ + j * h);
      }
    }
  };
  const int chunks = static_cast<int>(std::clamp<unsigned>(threads, 1u, 8u));
  std::vector<std::thread> pool;
  for (int t = 1; t < chunks; ++t) pool.emplace_back(fillRows, grid.rows_ * t / chunks, grid.rows_ * (t + 1) / chunks);
  fillRows(0, grid.rows_ / chunks);
  for (std::thread& t : pool) t.join();
  // The error where it is largest, mid-cell, over at most about 4,096 cells spread over the grid.
  const int cells = (grid.columns_ - 1) * (grid.rows_ - 1);
  const int stride = std::max(1, cells / 4096);
  for (int c = 0; c < cells; c += stride) {
    const double lon = grid.lon0_ + (c % (grid.columns_ - 1) + 0.5) * h;
    const double lat = grid.lat0_ + (c / (grid.columns_ - 1) + 0.5) * h;
    const glm::dvec2 d = grid.forward(lon, lat) - projection.forward(lon, lat);
    grid.measuredErrorM_ = std::max(grid.measuredErrorM_, std::sqrt(d.x * d.x + d.y * d.y));
  }
  if (!(grid.measuredErrorM_ <= kMaxErrorM)) return std::nullopt;
  return grid;
}

glm::dvec2 ProjectionGrid::forward(double lon, double lat) const {
  const double fx = (lon - lon0_) / kStepDegrees;
  const double fy = (lat - lat0_) / kStepDegrees;
  const int i = std::clamp(static_cast<int>(std::floor(fx)), 0, columns_ - 2);
  const int j = std::clamp(static_cast<int>(std::floor(fy)), 0, rows_ - 2);
  const double u = fx - i;
  const double v = fy - j;
  const std::size_t row =
      static_cast<std::size_t>(j) * static_cast<std::size_t>(columns_) + static_cast<std::size_t>(i);
  const glm::dvec2& a = nodes_[row];
  const glm::dvec2& b = nodes_[row + 1];
  const glm::dvec2& c = nodes_[row + static_cast<std::size_t>(columns_)];
  const glm::dvec2& d = nodes_[row + static_cast<std::size_t>(columns_) + 1];
  return a * ((1.0 - u) * (1.0 - v)) + b * (u * (1.0 - v)) + c * ((1.0 - u) * v) + d * (u * v);
}

}  // namespace qv::prep
