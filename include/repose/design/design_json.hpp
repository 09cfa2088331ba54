// A design's result as JSON (`repose design --json`, design.json, and Python's repose.design).
#pragma once

#include <string>

#include "repose/design/design.hpp"
#include "repose/design/target.hpp"
#include "repose/design/toss_design.hpp"

namespace repose {

/// "center-of-mass", "vertices", "faces", "vertices+center-of-mass" or "faces+center-of-mass".
std::string to_string(const DesignFreedom& freedom);

/// The design's JSON text (2-space indented): the start `source`, the target (its file), the options, every
/// outcome's normal with its target, start and achieved probabilities, the unassigned faces', the stop and
/// whether it reached the tolerance, the centre of mass, the solid's centroid and their offset, the hull's
/// size, and the history (each iteration's objective, error, step and rejected trials by reason).
std::string design_json(const std::string& source, const DesignTarget& target, const DesignOptions& options,
                        const DesignResult& result);

/// A tossed design's JSON text: design_json's keys for the tossed design's shape (their probabilities
/// quasi-static), "model": "tossed", "quasi_static_design" (the starting point: the same keys), and
/// "tossed": the toss, the stop, the settles, the checks of both designs on unseen drops (counts,
/// probability, ci95, χ²) and the history of tossed estimates.
std::string toss_design_json(const std::string& source, const DesignTarget& target,
                             const TossDesignOptions& options, const TossDesignResult& result);

}  // namespace repose
