// The shaking field of `quakeview-prep response` (private to prep::response): where each
// building's shaking comes from (the records as they are, a BSSA14 scenario or a ShakeMap), its
// travel-time delay, its target Sa(T1) and the site's own values kept in the summary (SITE).
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include <glm/vec2.hpp>

#include "qv/core/Result.h"
#include "qv/format/ResponseTile.h"
#include "qv/format/Tileset.h"
#include "qv/prep/DefaultSuite.h"
#include "qv/prep/Projection.h"
#include "qv/prep/ResponseRun.h"
#include "qv/prep/ShakeMap.h"
#include "qv/seismic/GroundMotionModel.h"
#include "qv/seismic/ResponseSpectrum.h"

namespace qv::prep::detail {

// Where each building's shaking comes from: the records as they are, a BSSA14 scenario or a ShakeMap.
class ShakingField {
 public:
  struct Site {
    double pgaG = 0.0;                     // the field's median PGA at the site (0 without a field)
    double delayS = 0.0;                   // S-wave travel time from the hypocentre
    seismic::SpectralOrdinates spectra{};  // ShakeMap values at the site (g)
    double distanceKm = 0.0;               // epicentral (Joyner-Boore for the point source)
    BuildingSite intensity;                // what the summary's SITE section keeps
  };

  ShakingField(const ResponseRunOptions& options, const Tileset& tileset, std::optional<ShakeMapGrid> grid)
      : options_(options), projection_(tileset.originLon, tileset.originLat), grid_(std::move(grid)) {
    if (options.scenario) {
      hasEpicentre_ = true;
      epicentre_ = projection_.forward(options.scenario->epicentreLongitudeDeg, options.scenario->epicentreLatitudeDeg);
      depthKm_ = options.scenario->depthKm;
      waveSpeed_ = options.scenario->shearWaveSpeedKmPerS;
    } else if (grid_ && std::isfinite(grid_->event.longitudeDeg) && std::isfinite(grid_->event.latitudeDeg)) {
      // (A grid without an epicentre: every building shakes from t = 0.)
      hasEpicentre_ = true;
      epicentre_ = projection_.forward(grid_->event.longitudeDeg, grid_->event.latitudeDeg);
      depthKm_ = std::isfinite(grid_->event.depthKm) ? grid_->event.depthKm : 0.0;
      waveSpeed_ = options.shearWaveSpeedKmPerS;
    }
  }

  [[nodiscard]] bool present() const { return options_.scenario.has_value() || grid_.has_value(); }
  [[nodiscard]] bool spectral() const { return present() && options_.scaleBy == ScaleBy::SpectralAcceleration; }

  /// The site at city coordinates (metres); nullopt outside the ShakeMap's grid.
  [[nodiscard]] Result<std::optional<Site>> site(double x, double y) const {
    Site s;
    if (!present()) return std::optional<Site>(s);
    s.distanceKm = std::hypot(x - epicentre_.x, y - epicentre_.y) / 1000.0;
    if (options_.scenario) {
      auto site = seismic::shakingAtSite(*options_.scenario, s.distanceKm, 1.0);
      if (!site.ok()) return Error{site.error()};
      s.pgaG = site->pgaG;
      s.delayS = site->delaySeconds;
      const seismic::Scenario& sc = *options_.scenario;
      auto psa = [&](double periodS) {
        return static_cast<float>(
            seismic::bssa14MedianPsaG(periodS, sc.magnitude, s.distanceKm, sc.vs30MetresPerSecond, sc.mechanism) *
            sc.siteFactor);
      };
      s.intensity.source = SiteSource::Scenario;
      s.intensity.pgaG = static_cast<float>(site->pgaG);
      s.intensity.psa03G = psa(0.3);
      s.intensity.psa10G = psa(1.0);
      s.intensity.psa30G = psa(3.0);
      s.intensity.vs30Mps = static_cast<float>(sc.vs30MetresPerSecond);
      return std::optional<Site>(s);
    }
    s.delayS = hasEpicentre_ ? seismic::shearWaveDelayS(s.distanceKm, depthKm_, waveSpeed_) : 0.0;
    const auto lonLat = projection_.reverse({x, y});
    const auto sample = sampleShakeMap(*grid_, lonLat[0], lonLat[1]);
    if (!sample) return std::optional<Site>();
    s.pgaG = sample->pgaG;
    s.spectra = {sample->pgaG, sample->psa03G, sample->psa10G, sample->psa30G};
    s.intensity.source = SiteSource::ShakeMap;
    s.intensity.pgaG = static_cast<float>(sample->pgaG);
    s.intensity.pgvCmS = static_cast<float>(sample->pgvCmS);
    s.intensity.psa03G = static_cast<float>(sample->psa03G);
    s.intensity.psa10G = static_cast<float>(sample->psa10G);
    s.intensity.psa30G = static_cast<float>(sample->psa30G);
    s.intensity.mmi = static_cast<float>(sample->mmi);
    s.intensity.vs30Mps = static_cast<float>(sample->vs30Mps);
    return std::optional<Site>(s);
  }

  /// The target 5 %-damped Sa (g) at `periodS` for a site.
  [[nodiscard]] double targetSaG(const Site& site, double periodS) const {
    if (options_.scenario) {
      const seismic::Scenario& sc = *options_.scenario;
      return seismic::bssa14MedianPsaG(periodS, sc.magnitude, site.distanceKm, sc.vs30MetresPerSecond, sc.mechanism) *
             sc.siteFactor;
    }
    return seismic::shakeMapTargetSaG(site.spectra, periodS);
  }

  /// Whether the default suite can be matched to the field's spectra: a scenario, or a ShakeMap
  /// with PSA fields.
  [[nodiscard]] bool matchable() const {
    return options_.scenario.has_value() || (grid_.has_value() && grid_->hasSpectra());
  }

  /// The quantised shape of a site's target (DefaultSuite.h); only when matchable().
  [[nodiscard]] SiteShape shape(const Site& site) const {
    return options_.scenario ? scenarioSiteShape(site.distanceKm) : shakeMapSiteShape(site.spectra);
  }

  [[nodiscard]] double maxDelayS(const Tileset& tileset) const {
    if (!hasEpicentre_) return 0.0;
    double maxDelay = 0.0;
    for (const auto& [cx, cy] :
         {std::pair{tileset.bounds.minX, tileset.bounds.minY}, std::pair{tileset.bounds.maxX, tileset.bounds.minY},
          std::pair{tileset.bounds.minX, tileset.bounds.maxY}, std::pair{tileset.bounds.maxX, tileset.bounds.maxY}}) {
      const double km = std::hypot(cx - epicentre_.x, cy - epicentre_.y) / 1000.0;
      maxDelay = std::max(maxDelay, seismic::shearWaveDelayS(km, depthKm_, waveSpeed_));
    }
    return maxDelay;
  }

  [[nodiscard]] const CityProjection& projection() const { return projection_; }

 private:
  const ResponseRunOptions& options_;
  CityProjection projection_;
  std::optional<ShakeMapGrid> grid_;
  bool hasEpicentre_ = false;
  glm::dvec2 epicentre_{0.0};
  double depthKm_ = 0.0;
  double waveSpeed_ = 3.5;
};

}  // namespace qv::prep::detail
