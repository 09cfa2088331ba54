// The target of an inverse design (issue 50, `repose design`): a probability per outcome, an outcome being
// the hull faces nearest an outward normal given in the body frame of the input mesh. The forms read are
// Baktash et al.'s (ACM TOG 44(4), 2025; their tool convex_dice): "normal → probability" pairs, so their
// targets can be used as they are; an object listing the outcomes by name; or "fair over these normals".
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "repose/geometry/hull.hpp"
#include "repose/geometry/types.hpp"

namespace repose {

struct DesignOutcome {
  Vec3 normal = Vec3::UnitZ();  ///< outward unit normal, body frame of the input mesh
  double probability = 0;       ///< the target probability of resting on one of `faces`
  std::vector<int> faces;       ///< hull faces assigned to it (assign_outcome_faces), ascending
};

struct DesignTarget {
  std::string source;  ///< where it was read from (parse_design_target's `source`): errors name it
  std::vector<DesignOutcome> outcomes;
  /// Hull faces assigned to no outcome (assign_outcome_faces): their target probability is 0.
  std::vector<int> unassigned_faces;
};

/// Reads a target from JSON text; `source` names it in errors (a file name). Accepted forms:
///   [[[nx, ny, nz], p], ...]                                  convex_dice's normal → probability pairs
///   {"outcomes": [{"normal": [nx, ny, nz], "probability": p}, ...]}
///   {"pairs": [...], ...}                                     the same list: convex_dice's JSON files
///   {"fair": [[nx, ny, nz], ...]}                             the same probability for each normal
/// Normals need not be unit (they are normalised) but must be finite and nonzero, and no two may be within
/// 1e-6 rad of each other; probabilities must be finite, in [0, 1] and sum to 1 within 1e-6. Throws
/// repose::Error with a one-line message naming `source` and the problem.
DesignTarget parse_design_target(std::string_view json_text, const std::string& source);

/// Assigns every hull face to the outcome whose normal is nearest its own (the largest cosine), if within
/// `max_angle` (rad); faces beyond it belong to no outcome. Throws repose::Error if an outcome gets no face:
/// its normal is not an outcome of this hull (the message gives the nearest face's angle, and
/// `angle_option`, the option that sets `max_angle`).
void assign_outcome_faces(DesignTarget& target, const ConvexHull& hull, double max_angle,
                          const std::string& angle_option);

/// The probability of each outcome (in the target's order) given a probability per hull face, then, as a
/// last entry, that of the unassigned faces.
std::vector<double> outcome_probabilities(const DesignTarget& target,
                                          const std::vector<double>& face_probability);

}  // namespace repose
