// Scenario shaking: a published ground-motion model for the median peak ground acceleration, and
// the per-building scale and delay that turn one input record into each building's excitation.
//
// Model: Boore, Stewart, Seyhan & Atkinson (2014), "NGA-West2 equations for predicting PGA, PGV, and
// 5 % damped PSA for shallow crustal earthquakes", Earthquake Spectra 30(3), 1057–1085 (BSSA14):
// median PGA in g from moment magnitude, the Joyner–Boore distance Rjb (km, the closest distance to
// the surface projection of the rupture; for the point source of a Scenario it is the epicentral
// distance), the fault mechanism and Vs30 (linear and nonlinear site terms; no basin term). The
// coefficients are the authors' revised table (2014-07-15): the PGA row, and the 5 %-damped PSA rows
// at 105 periods from 0.01 to 10 s. Validity: M 3–8.5, Rjb 0–400 km, Vs30 150–1500 m/s.
//
// Travel time: the S wave arrives after hypocentral distance / shear-wave speed (3.5 km/s by
// default, a typical upper-crust value), so the shaking sweeps across a city from the epicentre.
// The library works in kilometres; callers compute distances from projected coordinates.
#pragma once

#include "qv/core/Result.h"

namespace qv::seismic {

enum class FaultMechanism { Unspecified, StrikeSlip, Normal, Reverse };

/// BSSA14 median PGA in g. Preconditions (checked by `shakingAtSite`, clamped here): magnitude in
/// [3, 8.5], distance >= 0, vs30 in [150, 1500].
double bssa14MedianPgaG(double magnitude, double joynerBooreDistanceKm, double vs30MetresPerSecond,
                        FaultMechanism mechanism = FaultMechanism::Unspecified);

/// BSSA14 median 5 %-damped PSA (g, RotD50) at `periodS` (s). Same inputs, clamping, site terms
/// (linear, and nonlinear driven by the rock PGA, PGAr) and no basin term as `bssa14MedianPgaG`.
///   - periodS == 0: PGA (exactly `bssa14MedianPgaG`).
///   - 0 < periodS <= 0.01 s: the 0.01 s row (BSSA14's shortest tabulated period).
///   - 0.01..10 s: the revised coefficient table (Boore et al. 2014, Earthquake Spectra 30(3),
///     electronic supplement, 2014-07-15; 105 periods); at a tabulated period the table's value,
///     between two the prediction is interpolated linearly in ln(PSA) vs ln(T) between the
///     predictions at the two neighbouring tabulated periods.
///   - periodS > 10 s: extrapolated as PSA(10 s)·(10/T)² (constant spectral displacement, the
///     long-period branch of the ASCE 7-16 §11.4.6 design shape); outside the model's range.
/// NaN when periodS is negative or not finite.
double bssa14MedianPsaG(double periodS, double magnitude, double joynerBooreDistanceKm, double vs30MetresPerSecond,
                        FaultMechanism mechanism = FaultMechanism::Unspecified);

struct Scenario {
  double epicentreLongitudeDeg = 0.0;  ///< for the caller's projection; the model works in km
  double epicentreLatitudeDeg = 0.0;
  double depthKm = 10.0;   ///< hypocentral depth, [0, 700]
  double magnitude = 6.5;  ///< moment magnitude, [3, 8.5]
  FaultMechanism mechanism = FaultMechanism::Unspecified;
  double vs30MetresPerSecond = 760.0;  ///< 760 m/s: BSSA14's reference rock (site term zero)
  double siteFactor = 1.0;             ///< extra multiplier on the median PGA (> 0)
  double shearWaveSpeedKmPerS = 3.5;   ///< travel-time speed (> 0)
};

struct SiteShaking {
  double pgaG = 0.0;          ///< predicted median PGA at the site (g), site factor included
  double scale = 1.0;         ///< multiply the input record by this to reach pgaG
  double delaySeconds = 0.0;  ///< shift the input record by this (hypocentral distance / speed)
};

/// The S-wave travel time (s) to a site `epicentralDistanceKm` from the epicentre of a source
/// `depthKm` deep: hypocentral distance / speed. Preconditions: distances >= 0, speed > 0.
double shearWaveDelayS(double epicentralDistanceKm, double depthKm, double shearWaveSpeedKmPerS);

/// Shaking of a site at `epicentralDistanceKm` from the epicentre for an input record whose peak is
/// `recordPeakG` (g, > 0). Errors name the parameter that is out of range.
Result<SiteShaking> shakingAtSite(const Scenario& scenario, double epicentralDistanceKm, double recordPeakG);

}  // namespace qv::seismic
