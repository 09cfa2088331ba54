// A rest-pose study: what `repose poses` computes, writes and merges.
//
// The result file (JSON) records the particle, the settings, the pose catalogue and the raw tally, so that
// result files of disjoint drop ranges merge into exactly the file one run over their union writes (the
// "timing" object excepted).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "repose/model/params.hpp"
#include "repose/model/particle.hpp"
#include "repose/poses/ensemble.hpp"
#include "repose/poses/landscape.hpp"
#include "repose/poses/rest_poses.hpp"

namespace repose {

struct PosesStudy {
  // The particle, to check that merged files describe the same one.
  std::string source;       ///< mesh file or shape spec
  std::string fingerprint;  ///< geometry_fingerprint of the particle (hex); empty in files that predate it
  double density = 0;
  std::string inertia = "exact";       ///< the particle's inertia model (MeshOptions)
  double scale = 1;                    ///< the factor its file's coordinates were multiplied by
  bool repaired = false;               ///< its surface was repaired (MeshOptions::repair)
  std::optional<Vec3> center_of_mass;  ///< the centre of mass given for it (MeshOptions), if any
  double length = 0;                   ///< characteristic length L (length)
  double mass = 0;
  int hull_faces = 0;
  bool smooth = false;  ///< treated as smooth (the settling engine's smooth model)
  // Settings.
  SettleParams params;
  TossDistribution toss;  ///< tosses (issue 14); inactive: drops from rest
  bool decide_early = true;
  // Results.
  RestPoseCatalog catalog;  ///< face_pose is not recorded in the file
  EnsembleTally tally;
  int threads = 0;  ///< threads used (timing information)
};

/// How a study is set up: everything but the particle and the drops.
struct StudySettings {
  std::uint64_t seed = 1;
  PoseMethod method = PoseMethod::dynamic;
  double density = 1;   ///< mass per unit volume
  SettleParams params;  ///< params.damping is used only if damping_given
  bool damping_given = false;
  double damping_ratio = 0.05;  ///< otherwise C = damping_ratio · m · sqrt(g L³)
  double persistence = -1;      ///< pose-merge threshold as a fraction of L; < 0 = default_persistence
  bool decide_early = true;
  TossDistribution toss;  ///< drop i's toss: drop_toss(seed, i, toss)
};

/// The study of `particle` under `settings` with nothing counted yet (a tally of zero drops over its
/// catalogue): the header every result of that particle and those settings shares. Throws repose::Error for
/// invalid settings.
PosesStudy prepare_study(const Particle& particle, const RestLandscape& landscape,
                         const StudySettings& settings);

/// The options run_ensemble needs to add drops `drops` to a study prepared by prepare_study.
EnsembleOptions ensemble_options(const PosesStudy& study, DropRange drops, int threads);

/// A 64-bit FNV-1a hash of the particle's body-frame surface (vertex bits and triangles): results of
/// different meshes that happen to share a file name do not merge.
std::uint64_t geometry_fingerprint(const Particle& particle);

/// The result file: JSON with `n`, `seed`, `method`, `poses` [{`probability`, `ci95`, `count`,
/// `down_normal_body`, `com_height`, `orientation`, ...}], `status_counts`, ... and a `timing` object.
std::string poses_json(const PosesStudy& study);

/// Reads a result file back (`name` for messages). Throws repose::Error naming the file and the problem.
PosesStudy parse_poses_json(const std::string& text, const std::string& name);

/// One row per pose: the same numbers as the JSON, for spreadsheets.
std::string poses_csv(const PosesStudy& study);

/// A human-readable table.
std::string poses_table(const PosesStudy& study);

/// Throws repose::Error unless `a` and `b` are results of the same study (particle, settings, seed, method
/// and pose catalogue), so that their tallies may be merged.
void require_same_study(const PosesStudy& a, const PosesStudy& b);

/// The study of the union of two studies over disjoint drop ranges. Throws repose::Error if they describe
/// different particles, settings, seeds or methods, or if their ranges overlap.
PosesStudy merge_studies(const PosesStudy& a, const PosesStudy& b);

/// The order poses are reported in: most frequent first, then most likely quasi-statically, then catalogue
/// order.
std::vector<int> report_order(const PosesStudy& study);

}  // namespace repose
