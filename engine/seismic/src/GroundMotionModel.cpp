#include "qv/seismic/GroundMotionModel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace qv::seismic {
namespace {

// BSSA14, PGA row of the coefficient table (period "0"), revised 2014-07-15 (electronic supplement
// of Boore et al. 2014; also the PEER report 2013/05 Table). Global (California/Taiwan) anelastic
// term: Δc3 = 0.
struct Bssa14Pga {
  static constexpr double e0 = 0.4473, e1 = 0.4856, e2 = 0.2459, e3 = 0.4539;  // U, SS, NS, RS
  static constexpr double e4 = 1.431, e5 = 0.05053, e6 = -0.1662, mh = 5.5;
  static constexpr double c1 = -1.134, c2 = 0.1917, c3 = -0.008088, mref = 4.5, rref = 1.0, h = 4.5;
  static constexpr double clin = -0.6, vc = 1500.0, vref = 760.0;
  static constexpr double f1 = 0.0, f3 = 0.1, f4 = -0.15, f5 = -0.00701;
};

std::string formatDouble(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

double lnPgaRock(double m, double rjb, FaultMechanism mechanism) {
  using C = Bssa14Pga;
  double eventTerm = C::e0;
  switch (mechanism) {
    case FaultMechanism::Unspecified:
      eventTerm = C::e0;
      break;
    case FaultMechanism::StrikeSlip:
      eventTerm = C::e1;
      break;
    case FaultMechanism::Normal:
      eventTerm = C::e2;
      break;
    case FaultMechanism::Reverse:
      eventTerm = C::e3;
      break;
  }
  const double dm = m - C::mh;
  const double fe = dm <= 0.0 ? eventTerm + C::e4 * dm + C::e5 * dm * dm : eventTerm + C::e6 * dm;
  const double r = std::sqrt(rjb * rjb + C::h * C::h);
  const double fp = (C::c1 + C::c2 * (m - C::mref)) * std::log(r / C::rref) + C::c3 * (r - C::rref);
  return fe + fp;
}

}  // namespace

double bssa14MedianPgaG(double magnitude, double joynerBooreDistanceKm, double vs30, FaultMechanism mechanism) {
  using C = Bssa14Pga;
  const double m = std::clamp(magnitude, 3.0, 8.5);
  const double rjb = std::max(0.0, joynerBooreDistanceKm);
  const double v = std::clamp(vs30, 150.0, 1500.0);
  const double lnRock = lnPgaRock(m, rjb, mechanism);
  // Site: linear term, and the nonlinear term driven by the rock (Vs30 = 760 m/s) PGA.
  const double flin = C::clin * std::log(std::min(v, C::vc) / C::vref);
  const double f2 = C::f4 * (std::exp(C::f5 * (std::min(v, 760.0) - 360.0)) - std::exp(C::f5 * (760.0 - 360.0)));
  const double pgaRock = std::exp(lnRock);
  const double fnl = C::f1 + f2 * std::log((pgaRock + C::f3) / C::f3);
  return std::exp(lnRock + flin + fnl);
}

Result<SiteShaking> shakingAtSite(const Scenario& s, double epicentralDistanceKm, double recordPeakG) {
  auto bad = [](const char* what, double value, const char* range) {
    return fail(std::string("scenario: ") + what + " " + formatDouble(value) + " is outside " + range);
  };
  if (!(s.magnitude >= 3.0 && s.magnitude <= 8.5)) return bad("magnitude", s.magnitude, "[3, 8.5] (BSSA14)");
  if (!(s.depthKm >= 0.0 && s.depthKm <= 700.0)) return bad("depth (km)", s.depthKm, "[0, 700]");
  if (!(s.vs30MetresPerSecond >= 150.0 && s.vs30MetresPerSecond <= 1500.0))
    return bad("Vs30 (m/s)", s.vs30MetresPerSecond, "[150, 1500] (BSSA14)");
  if (!(s.siteFactor > 0.0 && s.siteFactor <= 100.0)) return bad("site factor", s.siteFactor, "(0, 100]");
  if (!(s.shearWaveSpeedKmPerS > 0.0 && s.shearWaveSpeedKmPerS <= 20.0))
    return bad("shear-wave speed (km/s)", s.shearWaveSpeedKmPerS, "(0, 20]");
  if (!(epicentralDistanceKm >= 0.0 && epicentralDistanceKm <= 400.0))
    return bad("distance (km)", epicentralDistanceKm, "[0, 400] (BSSA14)");
  if (!(recordPeakG > 0.0 && std::isfinite(recordPeakG))) return bad("record peak (g)", recordPeakG, "(0, inf)");
  SiteShaking out;
  out.pgaG = s.siteFactor * bssa14MedianPgaG(s.magnitude, epicentralDistanceKm, s.vs30MetresPerSecond, s.mechanism);
  out.scale = out.pgaG / recordPeakG;
  const double hypocentralKm = std::sqrt(epicentralDistanceKm * epicentralDistanceKm + s.depthKm * s.depthKm);
  out.delaySeconds = hypocentralKm / s.shearWaveSpeedKmPerS;
  return out;
}

}  // namespace qv::seismic
