// The tossed landings of a design by outcome, with their intervals and χ² (toss_design.hpp).
#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>
#include <cmath>

#include "repose/design/toss_design.hpp"
#include "repose/error.hpp"
#include "repose/poses/ensemble.hpp"
#include "repose/poses/landscape.hpp"
#include "tossed.hpp"

namespace repose {

namespace detail {

TossedOutcomes tossed_outcomes(const Particle& particle, const RestLandscape& landscape,
                               const DesignTarget& assigned, const TossModel& model, DropRange drops) {
  StudySettings settings = model.settings;
  settings.method = PoseMethod::dynamic;
  settings.persistence = 0;  // every stable face its own pose: a pose belongs to one outcome
  const PosesStudy study = prepare_study(particle, landscape, settings);
  EnsembleOptions options = ensemble_options(study, drops, model.threads);
  options.finish_representatives = false;  // only the counts are wanted
  options.cancel = model.cancel;
  const EnsembleTally tally = run_ensemble(particle, landscape, study.catalog, options);

  const std::size_t outcomes = assigned.outcomes.size();
  std::vector<std::uint64_t> counts(outcomes + 2, 0);
  std::uint64_t rested = 0;
  for (std::size_t p = 0; p < tally.poses.size(); ++p) {
    const int face = study.catalog.poses[p].face;
    std::size_t o = outcomes;  // the faces of no outcome
    for (std::size_t k = 0; k < outcomes; ++k)
      if (std::binary_search(assigned.outcomes[k].faces.begin(), assigned.outcomes[k].faces.end(), face))
        o = k;
    counts[o] += tally.poses[p].count;
    rested += tally.poses[p].count;
  }
  counts[outcomes + 1] = drops.size() - rested;
  std::vector<double> target;
  for (const auto& o : assigned.outcomes) target.push_back(o.probability);
  return summarise(drops, std::move(counts), target);
}

namespace {
constexpr double kZ95 = 1.959963984540054;  // the normal quantile at 0.975

// The normal quantile at 1 − 0.025/outcomes: Bonferroni's two-sided 95 % over the outcomes.
double bonferroni_z(std::size_t outcomes) {
  return outcomes > 0
             ? boost::math::quantile(boost::math::complement(boost::math::normal_distribution<double>(),
                                                             0.025 / static_cast<double>(outcomes)))
             : kZ95;
}
}  // namespace

TossedOutcomes summarise(DropRange drops, std::vector<std::uint64_t> counts,
                         const std::vector<double>& target) {
  const std::size_t outcomes = target.size();
  TossedOutcomes out;
  out.drops = drops;
  out.counts = std::move(counts);
  const double n = static_cast<double>(drops.size());
  std::uint64_t landed = 0;
  for (std::size_t k = 0; k < outcomes; ++k) landed += out.counts[k];
  bool within = out.counts[outcomes] == 0 && out.counts[outcomes + 1] == 0;
  bool within_all = within;
  const double z_all = bonferroni_z(outcomes);
  for (std::size_t k = 0; k < out.counts.size(); ++k) {
    out.probability.push_back(static_cast<double>(out.counts[k]) / n);
    out.ci95.push_back(wilson_interval(out.counts[k], drops.size()));
    if (k >= outcomes) continue;
    const double t = target[k];
    out.max_error = std::max(out.max_error, std::abs(out.probability[k] - t));
    within = within && out.ci95[k][0] <= t && t <= out.ci95[k][1];
    const auto all = wilson_interval(out.counts[k], drops.size(), z_all);
    within_all = within_all && all[0] <= t && t <= all[1];
    const double expected = t * static_cast<double>(landed);
    if (expected > 0) {
      out.chi_square += std::pow(static_cast<double>(out.counts[k]) - expected, 2) / expected;
    } else if (out.counts[k] > 0) {
      out.chi_square = INFINITY;  // landings where the target allows none
    }
  }
  out.all_within_ci95 = within;
  out.all_within_simultaneous = within_all;
  out.dof = static_cast<int>(outcomes) - 1;
  if (out.dof >= 1 && landed > 0) {
    out.p_value = std::isfinite(out.chi_square)
                      ? boost::math::cdf(boost::math::complement(
                            boost::math::chi_squared_distribution<double>(out.dof), out.chi_square))
                      : 0.0;
  }
  return out;
}

void count_fit_noise(TossedOutcomes& check, const std::vector<double>& target, std::uint64_t fit_drops) {
  const std::size_t outcomes = target.size();
  check.fit_drops = fit_drops;
  const double m = static_cast<double>(check.drops.size()), n = static_cast<double>(fit_drops);
  bool each = fit_drops > 0 && check.drops.size() > 0 && check.counts[outcomes] == 0 &&
              check.counts[outcomes + 1] == 0;
  bool all = each;
  const double z_all = bonferroni_z(outcomes);
  for (std::size_t k = 0; k < outcomes && all; ++k) {
    const double t = target[k];
    const double spread = std::sqrt(t * (1 - t) * (1 / n + 1 / m));
    const double off = std::abs(check.probability[k] - t);
    each = each && off <= kZ95 * spread;
    all = off <= z_all * spread;
  }
  check.all_within_fit_and_check = each;
  check.all_within_fit_and_check_simultaneous = all;
}

}  // namespace detail

TossedOutcomes tossed_outcomes(const Particle& particle, const DesignTarget& target, const TossModel& model,
                               DropRange drops, double outcome_angle) {
  if (drops.size() == 0) throw Error("design: the tossed estimate needs at least one drop");
  DesignTarget assigned = target;
  assign_outcome_faces(assigned, particle.hull, outcome_angle, "--outcome-angle");
  return detail::tossed_outcomes(particle, compute_rest_landscape(particle), assigned, model, drops);
}

}  // namespace repose
