// GeoFrame: the one transverse Mercator of the viewer and quakeview-prep.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <utility>

#include "qv/geometry/GeoFrame.h"

using qv::GeoFrame;
using qv::LonLat;

TEST_CASE("GeoFrame agrees with GeographicLib's published UTM example", "[geometry][geo]") {
  // GeoConvert(1)'s manual: 33.3°N 44.4°E is UTM 38N 444140.54 3684706.36. UTM zone 38 is this
  // projection with its central meridian at 45°E, scaled by k0 = 0.9996, plus a false easting of
  // 500 km; northings count from the equator. So a frame at (45°E, 0°) gives the UTM figures
  // without the false easting, divided by 0.9996 (the manual's centimetres: 6 mm here).
  const GeoFrame frame(45.0, 0.0);
  REQUIRE(frame.valid());
  const auto xy = frame.forward({44.4, 33.3});
  REQUIRE(xy.has_value());
  CHECK(xy->x == Approx((444140.54 - 500000.0) / 0.9996).margin(0.006));
  CHECK(xy->y == Approx(3684706.36 / 0.9996).margin(0.006));
  const auto back = frame.reverse({(444140.54 - 500000.0) / 0.9996, 3684706.36 / 0.9996});
  REQUIRE(back.has_value());
  CHECK(back->lon == Approx(44.4).margin(1e-7));  // 1e-7 degrees is about a centimetre
  CHECK(back->lat == Approx(33.3).margin(1e-7));
}

TEST_CASE("GeoFrame round-trips and puts the origin at (0, 0), x east and y north", "[geometry][geo]") {
  for (const auto& [lon0, lat0] : {std::pair{-73.997, 40.727}, std::pair{10.7, 59.9}, std::pair{151.2, -33.9}}) {
    INFO("origin " << lon0 << ", " << lat0);
    const GeoFrame frame(lon0, lat0);
    const auto origin = frame.forward({lon0, lat0});
    REQUIRE(origin.has_value());
    CHECK(origin->x == Approx(0.0).margin(1e-9));
    CHECK(origin->y == Approx(0.0).margin(1e-9));
    for (const auto& [dlon, dlat] : {std::pair{-0.02, -0.024}, std::pair{0.034, 0.032}, std::pair{0.007, 0.023}}) {
      const LonLat p{lon0 + dlon, lat0 + dlat};
      const auto xy = frame.forward(p);
      REQUIRE(xy.has_value());
      CHECK((xy->x > 0.0) == (dlon > 0.0));
      CHECK((xy->y > 0.0) == (dlat > 0.0));
      const auto back = frame.reverse(*xy);
      REQUIRE(back.has_value());
      CHECK(back->lon == Approx(p.lon).margin(1e-11));  // 1e-11 degrees is about a micrometre
      CHECK(back->lat == Approx(p.lat).margin(1e-11));
      // The unchecked conversions are the same numbers.
      CHECK(frame.forwardUnchecked(p) == *xy);
      CHECK(frame.reverseUnchecked(*xy).lon == back->lon);
      CHECK(frame.reverseUnchecked(*xy).lat == back->lat);
    }
  }
}

TEST_CASE("GeoFrame's checked conversions refuse what no city has", "[geometry][geo]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_FALSE(GeoFrame(0.0, 1000.0).valid());  // the viewer's frame before a manifest arrives
  CHECK_FALSE(GeoFrame(0.0, 1000.0).forward({0.0, 0.0}).has_value());
  CHECK_FALSE(GeoFrame(181.0, 0.0).valid());
  CHECK_FALSE(GeoFrame(nan, 0.0).valid());
  CHECK_FALSE(GeoFrame(0.0, 86.0).valid());
  const GeoFrame frame(-74.0, 40.7);
  CHECK_FALSE(frame.forward({nan, 40.7}).has_value());
  CHECK_FALSE(frame.forward({-74.0, 89.5}).has_value());
  CHECK_FALSE(frame.forward({-140.0, 40.7}).has_value());  // 66° from the central meridian
  CHECK_FALSE(frame.reverse({6.0e6, 0.0}).has_value());
  CHECK_FALSE(frame.reverse({0.0, nan}).has_value());
  // An origin beyond 85°, which quakeview-prep may use: the unchecked conversions still work.
  const GeoFrame polar(20.0, 87.0);
  CHECK_FALSE(polar.valid());
  const glm::dvec2 xy = polar.forwardUnchecked({20.5, 87.1});
  CHECK(xy.x > 0.0);
  CHECK(xy.y > 0.0);
  const LonLat back = polar.reverseUnchecked(xy);
  CHECK(back.lon == Approx(20.5).margin(1e-9));
  CHECK(back.lat == Approx(87.1).margin(1e-9));
}
