// Reading result files back: the pose records must name poses of the file's own catalogue.
#include "repose/poses/study.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <set>
#include <string>

#include "repose/error.hpp"
#include "repose/model/particle.hpp"
#include "repose/poses/landscape.hpp"

namespace {

using namespace repose;

// Replaces the single occurrence of `from` in `text`.
std::string replace_once(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// A box with three different edge lengths rests on any of its 6 faces (6 poses, indices 0..5). A file whose
// last record names pose 6, one past the end, must be rejected with the index named, not read into a pose
// that does not exist.
// The geometry fingerprint guards merges against results of another particle: the same geometry gives the
// same value, and a box changed in one coordinate by 1e-12 (a few ulps), for 200 such boxes, gives 200
// different values.
TEST(GeometryFingerprint, TellsApartGeometriesThatDifferInOneCoordinate) {
  EXPECT_EQ(geometry_fingerprint(load_particle("box:x=1,y=2,z=3", 1.0)),
            geometry_fingerprint(load_particle("box:x=1,y=2,z=3", 5.0)));  // density is not geometry
  std::set<std::uint64_t> seen;
  for (int k = 0; k < 200; ++k) {
    char spec[64];
    std::snprintf(spec, sizeof spec, "box:x=1,y=2,z=%.17g", 3 + k * 1e-12);
    seen.insert(geometry_fingerprint(load_particle(spec, 1.0)));
  }
  EXPECT_EQ(seen.size(), 200u);
}

TEST(PosesStudyFile, PoseIndexOnePastTheEndIsRejected) {
  const Particle particle = load_particle("box:x=1,y=2,z=3", 1.0);
  const RestLandscape landscape = compute_rest_landscape(particle);
  StudySettings settings;
  settings.method = PoseMethod::quasi_static;
  const PosesStudy study = prepare_study(particle, landscape, settings);
  ASSERT_EQ(study.catalog.poses.size(), 6u);
  const std::string text = poses_json(study);
  const PosesStudy back = parse_poses_json(text, "good.json");  // every index 0..5 is in range
  EXPECT_EQ(back.catalog.poses.size(), 6u);
  const std::string bad = replace_once(text, "\"pose\": 5,", "\"pose\": 6,");
  try {
    parse_poses_json(bad, "bad.json");
    ADD_FAILURE() << "pose index 6 of 6 poses was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.json: pose index 6 out of range"), std::string::npos)
        << e.what();
  }
}

// The integrator and its tolerance are settings of a result file: they are written, read back, and results of
// different integrators do not merge (their drops are not the same runs). A file from before the adaptive
// integrator existed (no "integrator" field) was computed with the paper's.
TEST(PosesStudyFile, TheIntegratorIsASettingThatRoundTripsAndBlocksMerging) {
  const Particle particle = load_particle("box:x=1,y=2,z=3", 1.0);
  const RestLandscape landscape = compute_rest_landscape(particle);
  StudySettings settings;
  settings.params.integrator = Integrator::paper;
  settings.params.tolerance = 3e-10;
  const PosesStudy paper = prepare_study(particle, landscape, settings);
  const PosesStudy back = parse_poses_json(poses_json(paper), "paper.json");
  EXPECT_EQ(back.params.integrator, Integrator::paper);
  EXPECT_EQ(back.params.tolerance, 3e-10);
  settings.params.integrator = Integrator::adaptive;
  const PosesStudy adaptive = prepare_study(particle, landscape, settings);
  EXPECT_EQ(parse_poses_json(poses_json(adaptive), "a.json").params.integrator, Integrator::adaptive);
  EXPECT_THROW(merge_studies(paper, adaptive), Error);
  const std::string old = replace_once(poses_json(adaptive), "\"integrator\": \"adaptive\",", "");
  EXPECT_EQ(parse_poses_json(old, "old.json").params.integrator, Integrator::paper);
}

// A merged result reports the most threads any of its parts ran on, whichever order they are merged in.
TEST(PosesStudyFile, AMergeReportsTheLargestThreadCount) {
  const Particle particle = load_particle("box:x=1,y=2,z=3", 1.0);
  const RestLandscape landscape = compute_rest_landscape(particle);
  PosesStudy one = prepare_study(particle, landscape, StudySettings{});
  PosesStudy two = one;
  one.threads = 1;
  one.tally.ranges = {{0, 10}};
  two.threads = 2;
  two.tally.ranges = {{10, 20}};
  EXPECT_EQ(merge_studies(one, two).threads, 2);
  EXPECT_EQ(merge_studies(two, one).threads, 2);
}

}  // namespace
