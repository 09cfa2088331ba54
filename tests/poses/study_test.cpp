// Reading result files back: the pose records must name poses of the file's own catalogue.
#include "repose/poses/study.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

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

// A drop range holds at least one drop: an empty or reversed one in a file (edited by hand) is refused by
// name, before it could make `n` wrap around or let a merge's overlap test pass ranges in either order.
TEST(PosesStudyFile, EmptyOrReversedDropRangesAreRejected) {
  const Particle particle = load_particle("box:x=1,y=2,z=3", 1.0);
  const RestLandscape landscape = compute_rest_landscape(particle);
  StudySettings settings;
  settings.method = PoseMethod::quasi_static;
  const std::string text = poses_json(prepare_study(particle, landscape, settings));
  ASSERT_NE(text.find("\"drop_ranges\": []"), std::string::npos);
  for (const auto& [ranges, shown] : std::vector<std::pair<std::string, std::string>>{
           {"[[5, 5]]", "[5, 5)"}, {"[[10, 5]]", "[10, 5)"}, {"[[0, 3], [7, 7]]", "[7, 7)"}}) {
    const std::string bad = replace_once(text, "\"drop_ranges\": []", "\"drop_ranges\": " + ranges);
    try {
      parse_poses_json(bad, "edited.json");
      ADD_FAILURE() << ranges << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("edited.json: drop range " + shown + " is empty or reversed"),
                std::string::npos)
          << e.what();
    }
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

// A centre of mass given for the particle is part of its identity in a result file: written, read back, and
// results with another (or none) do not merge.
TEST(PosesStudyFile, AGivenCentreOfMassRoundTripsAndBlocksMerging) {
  MeshOptions options;
  options.center_of_mass = Vec3(0.1, 0, -0.2);
  const Particle weighted = load_particle("box:x=1,y=2,z=3", 1.0, options);
  const Particle plain = load_particle("box:x=1,y=2,z=3", 1.0);
  const PosesStudy a = prepare_study(weighted, compute_rest_landscape(weighted), StudySettings{});
  const PosesStudy b = prepare_study(plain, compute_rest_landscape(plain), StudySettings{});
  const PosesStudy back = parse_poses_json(poses_json(a), "a.json");
  ASSERT_TRUE(back.center_of_mass.has_value());
  EXPECT_EQ(*back.center_of_mass, Vec3(0.1, 0, -0.2));
  EXPECT_FALSE(parse_poses_json(poses_json(b), "b.json").center_of_mass.has_value());
  EXPECT_THROW(require_same_study(a, b), Error);
  EXPECT_NO_THROW(require_same_study(a, back));
}

// The CSV and the table of a result give each pose's probability with its 95 % Wilson interval, against the
// closed form (p + z²/2n ± z·sqrt(p(1 − p)/n + z²/4n²))/(1 + z²/n), z = 1.959963984540054, to 1e-15 (the CSV
// prints 17 digits) and to the table's 5 decimals.
TEST(PosesStudyFile, CsvAndTableGiveEachPoseItsWilsonInterval) {
  const Particle particle = load_particle("box:x=1,y=2,z=3", 1.0);
  const RestLandscape landscape = compute_rest_landscape(particle);
  PosesStudy s = prepare_study(particle, landscape, StudySettings{});
  ASSERT_GE(s.tally.poses.size(), 2u);
  const double n = 100;
  s.tally.ranges = {{0, 100}};
  s.tally.status_counts[1] = 100;
  s.tally.poses[0].count = 30;
  s.tally.poses[1].count = 70;
  const double z = 1.959963984540054;
  auto wilson = [&](double k, int sign) {
    const double p = k / n;
    return (p + z * z / (2 * n) + sign * z * std::sqrt(p * (1 - p) / n + z * z / (4 * n * n))) /
           (1 + z * z / n);
  };
  std::istringstream csv(poses_csv(s));
  std::string line;
  std::getline(csv, line);
  ASSERT_EQ(line.rfind("pose,face,count,probability,ci95_lo,ci95_hi,", 0), 0u) << line;
  int checked = 0;
  while (std::getline(csv, line)) {
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    const int pose = std::stoi(cells[0]);
    const double k = static_cast<double>(s.tally.poses[static_cast<std::size_t>(pose)].count);
    EXPECT_EQ(std::stod(cells[2]), k) << line;
    EXPECT_NEAR(std::stod(cells[3]), k / n, 1e-15) << line;
    EXPECT_NEAR(std::stod(cells[4]), wilson(k, -1), 1e-15) << line;
    EXPECT_NEAR(std::stod(cells[5]), wilson(k, +1), 1e-15) << line;
    ++checked;
  }
  EXPECT_EQ(checked, static_cast<int>(s.catalog.poses.size()));
  char row70[64];
  std::snprintf(row70, sizeof row70, "0.70000  [%.5f, %.5f]", wilson(70, -1), wilson(70, +1));
  EXPECT_NE(poses_table(s).find(row70), std::string::npos) << poses_table(s);
  // Poses with no drops and a quasi-static probability below 1e-4 are left out of the table, and counted;
  // with none left out there is no such line.
  EXPECT_EQ(poses_table(s).find("rarer poses"), std::string::npos) << poses_table(s);
  s.catalog.poses[2].quasi_static_probability = 1e-5;
  s.catalog.poses[3].quasi_static_probability = 0.5e-4;
  EXPECT_NE(poses_table(s).find("(2 rarer poses with no drops"), std::string::npos) << poses_table(s);
  // The last line: the run's time and rate, n / seconds (0 when no time was measured).
  s.tally.seconds = 0.5;
  s.threads = 2;
  EXPECT_NE(poses_table(s).find("time       0.500 s, 200.0 drops/s on 2 threads"), std::string::npos)
      << poses_table(s);
  s.tally.seconds = 0;
  EXPECT_NE(poses_table(s).find("time       0.000 s, 0.0 drops/s on 2 threads"), std::string::npos)
      << poses_table(s);
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

// Results whose rest-pose catalogues differ do not merge, even with as many poses (a pose's counts are only
// comparable if it groups the same hull faces): one pose's faces, any one of them, replaced by another's.
TEST(PosesStudyFile, AMergeRefusesAnotherCatalogueOfTheSameSize) {
  const Particle particle = load_particle("box:x=1,y=2,z=3", 1.0);
  const RestLandscape landscape = compute_rest_landscape(particle);
  PosesStudy one = prepare_study(particle, landscape, StudySettings{});
  one.tally.ranges = {{0, 10}};
  const std::size_t n = one.catalog.poses.size();
  ASSERT_GE(n, 2u);
  for (std::size_t p = 0; p < n; ++p) {
    PosesStudy two = one;
    two.tally.ranges = {{10, 20}};
    two.catalog.poses[p].faces = one.catalog.poses[(p + 1) % n].faces;
    ASSERT_NE(two.catalog.poses[p].faces, one.catalog.poses[p].faces);
    try {
      merge_studies(one, two);
      ADD_FAILURE() << "catalogues with other faces for pose " << p << " were merged";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("rest-pose catalogues"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
