// A design's HTML report (`repose design --html`): target against achieved per outcome (and, for a tossed
// design, both designs' tossed checks with their intervals), the design drawn in each of its rest poses, and
// the optimisation's history. Self-contained, as every repose report (repose/output/html.hpp).
#pragma once

#include <string>

#include "repose/design/design.hpp"
#include "repose/design/target.hpp"
#include "repose/model/particle.hpp"

namespace repose {

/// The designed body as a particle of its own: the design's hull (the input mesh's frame) with its centre of
/// mass, a uniform solid's inertia about it.
Particle design_particle(const DesignResult& design, const std::string& name);

/// The report's page. `design_json` is the design's JSON (design_json or toss_design_json) and `design` the
/// result it describes; outcomes are assigned to the design's faces within options.outcome_angle.
std::string design_report_html(const std::string& title, const DesignTarget& target,
                               const DesignOptions& options, const DesignResult& design,
                               const std::string& design_json);

}  // namespace repose
