// The tossed estimate of a design point (tossed_outcomes.cpp), for the toss design (toss_design.cpp).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "repose/design/toss_design.hpp"
#include "repose/poses/landscape.hpp"

namespace repose::detail {

// `assigned`: the target with its outcomes' faces assigned to this particle's hull.
TossedOutcomes tossed_outcomes(const Particle& particle, const RestLandscape& landscape,
                               const DesignTarget& assigned, const TossModel& model, DropRange drops);

// The estimate from its counts (per outcome, then the faces of no outcome, then the drops that did not rest)
// and the target's probability per outcome: frequencies, Wilson intervals, Pearson's χ².
TossedOutcomes summarise(DropRange drops, std::vector<std::uint64_t> counts,
                         const std::vector<double>& target);

// Sets `check`'s fit_drops and its fit-and-check flags (TossedOutcomes) for a design fitted on `fit_drops`.
void count_fit_noise(TossedOutcomes& check, const std::vector<double>& target, std::uint64_t fit_drops);

// The Jacobian J (outcomes × outcomes) with J·dq ≈ dp over the columns of finite differences dq (changes of
// the quasi-static probabilities, each summing to ~0) and dp (the tossed changes), least squares, acting on
// changes that keep Σq = 1 alone (J·𝟙 = 0).
Eigen::MatrixXd difference_jacobian(const Eigen::MatrixXd& dq, const Eigen::MatrixXd& dp);

}  // namespace repose::detail
