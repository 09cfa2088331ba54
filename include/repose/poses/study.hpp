// A rest-pose study: what `repose poses` computes, writes and merges.
//
// The result file (JSON) records the particle, the settings, the pose catalogue and the raw tally, so that
// result files of disjoint drop ranges merge into exactly the file one run over their union writes (the
// "timing" object excepted).
#pragma once

#include <string>

#include "repose/model/params.hpp"
#include "repose/model/particle.hpp"
#include "repose/poses/ensemble.hpp"
#include "repose/poses/rest_poses.hpp"

namespace repose {

struct PosesStudy {
  // The particle, to check that merged files describe the same one.
  std::string source;  ///< mesh file or shape spec
  double density = 0;
  double length = 0;  ///< characteristic length L (length)
  double mass = 0;
  int hull_faces = 0;
  bool smooth = false;  ///< treated as smooth (the settling engine's smooth model)
  // Settings.
  SettleParams params;
  bool decide_early = true;
  // Results.
  RestPoseCatalog catalog;  ///< face_pose is not recorded in the file
  EnsembleTally tally;
  int threads = 0;  ///< threads used (timing information)
};

/// The result file: JSON with `n`, `seed`, `method`, `poses` [{`probability`, `ci95`, `count`,
/// `down_normal_body`, `com_height`, `orientation`, ...}], `status_counts`, ... and a `timing` object.
std::string poses_json(const PosesStudy& study);

/// Reads a result file back (`name` for messages). Throws repose::Error naming the file and the problem.
PosesStudy parse_poses_json(const std::string& text, const std::string& name);

/// One row per pose: the same numbers as the JSON, for spreadsheets.
std::string poses_csv(const PosesStudy& study);

/// A human-readable table.
std::string poses_table(const PosesStudy& study);

/// The study of the union of two studies over disjoint drop ranges. Throws repose::Error if they describe
/// different particles, settings, seeds or methods, or if their ranges overlap.
PosesStudy merge_studies(const PosesStudy& a, const PosesStudy& b);

/// The order poses are reported in: most frequent first, then most likely quasi-statically, then catalogue
/// order.
std::vector<int> report_order(const PosesStudy& study);

}  // namespace repose
