#include "qv/scene/ViewConsequences.h"

#include <algorithm>
#include <cmath>

namespace qv {
namespace {

// z of the 95th percentile of the standard normal: a two-sided 90 % interval.
constexpr double kZ90 = 1.6448536269514722;

seismic::Estimate estimate(double mean, double variance, double upper) {
  const double half = kZ90 * std::sqrt(std::max(variance, 0.0));
  return {mean, std::max(0.0, mean - half), std::min(upper, mean + half)};
}

}  // namespace

void ConsequenceSums::add(const BuildingLoss& loss) {
  ++buildings_;
  auto bernoulli = [](double p) { return p * (1.0 - p); };
  for (std::size_t k = 0; k < 5; ++k) {
    const double p = loss.structural[k];
    states_[k].add(p, bernoulli(p));
  }
  collapsed_.add(loss.collapse, bernoulli(loss.collapse));
  for (std::size_t k = 0; k < 3; ++k) tags_[k].add(loss.tag[k], bernoulli(loss.tag[k]));
  cost_.add(loss.repairCostUsd, static_cast<double>(loss.repairCostStdUsd) * loss.repairCostStdUsd);
  for (std::size_t k = 0; k < 4; ++k) {
    injuries_[k].add(loss.injuries[k], static_cast<double>(loss.injuriesStd[k]) * loss.injuriesStd[k]);
  }
  occupants_ += loss.occupants;
}

seismic::LossTotals ConsequenceSums::totals() const {
  seismic::LossTotals t;
  t.buildings = buildings_;
  const auto n = static_cast<double>(buildings_);
  for (std::size_t k = 0; k < 5; ++k) t.damageStates[k] = estimate(states_[k].mean, states_[k].variance, n);
  t.collapsed = estimate(collapsed_.mean, collapsed_.variance, n);
  for (std::size_t k = 0; k < 3; ++k) t.tags[k] = estimate(tags_[k].mean, tags_[k].variance, n);
  t.repairCostUsd = estimate(cost_.mean, cost_.variance, HUGE_VAL);
  for (std::size_t k = 0; k < 4; ++k) t.injuries[k] = estimate(injuries_[k].mean, injuries_[k].variance, HUGE_VAL);
  t.occupants = {occupants_, occupants_, occupants_};
  return t;
}

}  // namespace qv
