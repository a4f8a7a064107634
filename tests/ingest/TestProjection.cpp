// The city frame: transverse Mercator with true metres near the city.
#include <catch2/catch.hpp>

#include <cmath>
#include <tuple>

#include <GeographicLib/Geodesic.hpp>
#include <glm/geometric.hpp>

#include "IngestTestData.h"
#include "qv/prep/Projection.h"

using namespace qv::prep;
using namespace qv::prep::test;

namespace {

double geodesicMeters(double lon1, double lat1, double lon2, double lat2) {
  double meters = 0.0;
  GeographicLib::Geodesic::WGS84().Inverse(lat1, lon1, lat2, lon2, meters);
  return meters;
}

}  // namespace

TEST_CASE("The tools project exactly as the viewer does", "[ingest][projection]") {
  // CityProjection is GeoFrame (engine/geometry, tested there: round trips, a published UTM point)
  // without the checks: the same numbers, bit for bit, so a building sits where the viewer's
  // coordinates say. Also for an origin beyond the viewer's 85°.
  for (const auto& [lon0, lat0] : {std::pair{-73.997, 40.727}, std::pair{151.2, -33.9}, std::pair{20.0, 87.0}}) {
    const CityProjection projection(lon0, lat0);
    const qv::GeoFrame frame(lon0, lat0);
    CHECK(projection.originLon() == lon0);
    CHECK(projection.originLat() == lat0);
    for (const auto& [lon, lat] : {std::pair{lon0 - 0.02, lat0 - 0.024}, std::pair{lon0 + 0.034, lat0 + 0.032}}) {
      const glm::dvec2 xy = projection.forward(lon, lat);
      CHECK(xy == frame.forwardUnchecked({lon, lat}));
      if (frame.valid()) CHECK(xy == frame.forward({lon, lat}).value());
      const auto back = projection.reverse(xy);
      CHECK(back[0] == Approx(lon).margin(1e-11));  // 1e-11 degrees is about a micrometre
      CHECK(back[1] == Approx(lat).margin(1e-11));
      CHECK(back[0] == frame.reverseUnchecked(xy).lon);
      CHECK(back[1] == frame.reverseUnchecked(xy).lat);
    }
  }
}

TEST_CASE("Projected distances are true metres (geodesic within 0.05 %)", "[ingest][projection]") {
  // Across the whole of the Lower Manhattan file: the Battery to 59th Street and the Hudson to
  // the East River, with the origin at the centre of the data.
  const CityProjection projection(-73.997, 40.727);
  const std::pair<double, double> a{-74.0170, 40.7033};
  const std::pair<double, double> b{-73.9630, 40.7590};
  const double planar = glm::length(projection.forward(b.first, b.second) - projection.forward(a.first, a.second));
  const double geodesic = geodesicMeters(a.first, a.second, b.first, b.second);
  CHECK(std::abs(planar - geodesic) / geodesic < 0.0005);
  // Plain (Web) Mercator would be off by 1 / cos(latitude): 32 % here.
  const double mercatorScale = 1.0 / std::cos(40.73 * M_PI / 180.0);
  CHECK(mercatorScale > 1.3);
}

TEST_CASE("The projection grid agrees with the exact projection within a millimetre", "[ingest][projection]") {
  // A city far from its central meridian and at a high latitude too, where the second derivatives
  // are largest.
  for (const auto& [lon0, lat0, span] :
       {std::tuple{-73.997, 40.727, 0.08}, std::tuple{10.7, 59.9, 0.5}, std::tuple{151.2, -33.9, 1.0}}) {
    INFO("origin " << lon0 << ", " << lat0 << ", span " << span);
    const CityProjection projection(lon0, lat0);
    const double minLon = lon0 - span / 2, minLat = lat0 - span / 2, maxLon = lon0 + span * 2, maxLat = lat0 + span;
    const auto grid = ProjectionGrid::make(projection, minLon, minLat, maxLon, maxLat, 10'000'000, 2);
    REQUIRE(grid.has_value());
    CHECK(grid->measuredErrorM() < 0.0002);
    double worst = 0.0;
    for (int k = 0; k <= 2000; ++k) {
      // Spread over the box, corners and edges included.
      const double u = k == 2000 ? 1.0 : std::fmod(k * 0.618034, 1.0),
                   v = k == 2000 ? 1.0 : std::fmod(k * 0.414214, 1.0);
      const double lon = minLon + u * (maxLon - minLon), lat = minLat + v * (maxLat - minLat);
      worst = std::max(worst, glm::length(grid->forward(lon, lat) - projection.forward(lon, lat)));
    }
    CHECK(worst < ProjectionGrid::kMaxErrorM);
  }
}

TEST_CASE("A projection grid that would be too large is not made", "[ingest][projection]") {
  const CityProjection projection(-73.997, 40.727);
  // 0.08 x 0.06 degrees at 0.001 degrees: about 83 x 63 nodes.
  CHECK(ProjectionGrid::make(projection, -74.03, 40.70, -73.95, 40.76, 1000).has_value() == false);
  const auto grid = ProjectionGrid::make(projection, -74.03, 40.70, -73.95, 40.76, 10000);
  REQUIRE(grid.has_value());
  CHECK(grid->nodes() < 10000);
  CHECK_FALSE(ProjectionGrid::make(projection, -73.9, 40.70, -74.0, 40.76, 10000).has_value());  // min > max
}

TEST_CASE("Building centroids of the PBF keep their geodesic distance", "[ingest][projection][data]") {
  const Ingested& in = manhattanSouth();
  REQUIRE(in.model.ok());
  const qv::prep::CityModel& model = *in.model;
  // The origin is the centre of the data's bounds (lon -74.031..-73.963, lat 40.695..40.759).
  CHECK(model.originLon == Approx(-73.997).margin(0.005));
  CHECK(model.originLat == Approx(40.727).margin(0.005));
  CHECK(model.projection == "transverse-mercator");
  const CityProjection projection(model.originLon, model.originLat);
  // The Empire State Building (Midtown) and the Battery Maritime Building (the southern tip),
  // about 5.5 km apart.
  const qv::prep::Building* esb = findBuilding(model, "w34633854");
  const qv::prep::Building* battery = findBuilding(model, "w169362470");
  REQUIRE(esb != nullptr);
  REQUIRE(battery != nullptr);
  const glm::dvec2 p{esb->attributes.centroidX, esb->attributes.centroidY};
  const glm::dvec2 q{battery->attributes.centroidX, battery->attributes.centroidY};
  const auto pl = projection.reverse(p);
  const auto ql = projection.reverse(q);
  const double geodesic = geodesicMeters(pl[0], pl[1], ql[0], ql[1]);
  CHECK(geodesic > 5000.0);
  CHECK(std::abs(glm::length(p - q) - geodesic) / geodesic < 0.0005);
  // And the ESB's centroid lies where its nodes are: 34th Street and Fifth Avenue.
  CHECK(pl[0] == Approx(-73.9857).margin(0.0005));
  CHECK(pl[1] == Approx(40.7484).margin(0.0005));
}
