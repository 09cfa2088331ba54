// The measuring stick: repose against Bullet, drop for drop (issue 12, deliverable 1).
//
// For each shape, drop i of the seed starts both engines at repose::drop_orientation(seed, i), from rest,
// with the lowest point touching the wall, under the same gravity (SI, g = 9.81 m/s², density 1000 kg/m³, the
// particle in metres, scaled to a characteristic length L of --length metres, default 0.5: the middle of the
// 0.1–1 m range Bullet is tuned for; --length natural keeps the shapes' own sizes, L 0.6–2.3 m). Per shape it
// prints the time per settle of each engine, their ratio, the set-up each pays once per particle, Bullet's
// maximum penetration and both rest-face histograms, classified by repose's rest-pose catalogue.
//
// Bullet's step (issue 35): by default each shape runs at every step of bullet_steps.hpp's candidates,
// 1/60 s (Bullet's default) to 1/1000 s, and is timed at the largest whose rest-pose histogram agrees with
// the finest's (χ² homogeneity, p ≥ 0.05: its cheapest trustworthy answer); the ratio at 1 ms is printed
// beside it. --bullet-step S runs Bullet at S seconds only.
//
//   repose: the `repose poses` defaults (damping ratio 0.05, decide early; --full-settle: to rest), through
//           repose::simulate_drop, exactly as a `repose poses` worker runs a drop.
//   Bullet: btDiscreteDynamicsWorld, btStaticPlaneShape ground at z = 0, the particle a btConvexHullShape of
//           repose's hull vertices in the principal frame with repose's exact mass and principal moments;
//           Bullet's defaults otherwise (collision margin, friction 0.5, restitution 0, no damping, solver
//           settings, deactivation); a fixed step stepSimulation(dt, 0). It starts with the lowest point of
//           its collision shape (the hull grown by the margin, 0.04 m) touching the plane. A drop ends at the
//           first 0.1 s window whose mean |v| and |ω| are below 1e-3·sqrt(g·L) and 1e-3·sqrt(g/L) and not
//           growing (second half of the window no faster than the first), or when Bullet puts the body to
//           sleep, or at 20 s of simulated time (counted as "no rest").
//
// --toss E,MU: both engines toss drop i instead of starting it at rest on the wall: released with its lowest
// point 4·L above the wall (Bullet: of its collision shape) with the centre-of-mass velocity and the angular
// velocity of repose::drop_toss(seed, i) (speeds up to 1.5·sqrt(g·L) and 1.5·sqrt(g/L), the toss model of
// docs/experiments.md). repose: restitution E and friction μ (its frictional contact phase after the
// landing). Bullet: the body's restitution E and friction μ, the ground's 1 and 1 (Bullet multiplies the two
// bodies' coefficients); Bullet's restitution is Newton's, equal to Stronge's E in a frictionless central
// impact. Bullet's impacts slower than its restitution velocity threshold (btContactSolverInfo, 0.2 of its
// units a second) are plastic; --match-threshold gives repose the same cut-off
// (SettleParams::restitution_threshold), which ends the long cascade of small rebounds that E near 1
// otherwise makes in repose.
//
// Bullet's units (--bullet-units, issue 49): metres, or centimetres, the unit a Bullet user picks for bodies
// of a centimetre (the body about one unit, so that Bullet's default margin, sleeping and restitution
// thresholds, all in its units, fit it); by default centimetres when the shapes are scaled below 0.1 m, the
// bottom of the range Bullet is tuned for in metres. Lengths, speeds and gravity are converted, masses stay
// in kg and times in s; what is reported is in metres.
//
// One thread for everything. Time per settle is steady_clock time over the N drops; for Bullet only the
// drop's reset, its steps and the rest test are timed, not the penetration measurement (a scan of every hull
// vertex after every step, which Bullet itself does not need). Set-up is timed apart: repose's is what
// `repose poses` pays once per particle (the particle from its mesh: hull, mass properties; the rest-pose
// landscape and catalogue; the study); Bullet's is its world and convex-hull shape, given repose's hull
// vertices and mass properties for free.
//
// Run:  build/release/bench/peers/repose_peer_bullet [--drops N] [--seed S] [--only NAME[,NAME...]]
//                                                    [--full-settle] [--toss E,MU [--match-threshold]]
//                                                    [--length L|natural] [--bullet-step S] [--meshes FILE]
//                                                    [--bullet-units m|cm|auto] [--bullet-no-sleep]
//                                                    [--bullet-damping]
//                                                    [--export FILE] [--trace] [--no-histograms]
//                                                    (--help: what they do)
// Figures and discussion: docs/performance.md ("Against Bullet").
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <numbers>
#include <random>
#include <repose/error.hpp>
#include <repose/geometry/shapes.hpp>
#include <repose/poses/ensemble.hpp>
#include <repose/poses/landscape.hpp>
#include <repose/poses/rest_poses.hpp>
#include <repose/poses/sampling.hpp>
#include <repose/poses/study.hpp>
#include <repose/repose.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "bullet_side.hpp"
#include "bullet_steps.hpp"
#include "peer_export.hpp"
#include "peer_report.hpp"
#include "peer_shapes.hpp"
#include "peer_usage.hpp"

namespace {

using namespace peer;  // the shared units, options and Bullet's side (bullet_side.hpp)
using repose::Quat;
using repose::Vec3;

// repose's side of the comparison: everything `repose poses` prepares once per particle.
struct ReposeSide {
  repose::RestLandscape landscape;
  repose::PosesStudy study;
  repose::EnsembleOptions options;
};

ReposeSide prepare_repose(const repose::Particle& particle, bool full_settle, const TossOptions& toss) {
  ReposeSide side;
  side.landscape = repose::compute_rest_landscape(particle);
  repose::StudySettings settings;  // the `repose poses` defaults: seed 1, damping ratio 0.05, decide early
  settings.density = kDensity;
  settings.params.gravity = kGravity;
  settings.decide_early = !full_settle;
  if (toss.active) {
    const double L = particle.length;
    settings.params.restitution = toss.restitution;
    settings.params.friction = toss.friction;
    settings.params.restitution_threshold = toss.threshold;
    settings.params.drop_height = TossOptions::kHeight * L;
    settings.toss.velocity_max = TossOptions::kVelocity * std::sqrt(kGravity * L);
    settings.toss.spin_max = TossOptions::kSpin * std::sqrt(kGravity / L);
  }
  side.study = repose::prepare_study(particle, side.landscape, settings);
  side.options = repose::ensemble_options(side.study, {0, 0}, 1);
  return side;
}

// The hull face whose outward normal is nearest `down` (body frame), and the angle between them.
std::pair<int, double> nearest_face(const repose::Particle& particle, const Vec3& down) {
  int best = -1;
  double best_dot = -2;
  for (int f = 0; f < static_cast<int>(particle.hull.faces.size()); ++f) {
    const double d = particle.hull.faces[f].normal.dot(down);
    if (d > best_dot) best_dot = d, best = f;
  }
  return {best, std::acos(std::clamp(best_dot, -1.0, 1.0))};
}

// Bullet's N drops at one step, classified by repose's catalogue and compared with repose's poses.
BulletRun run_bullet(const repose::Particle& particle, const ReposeSide& rs,
                     const std::vector<int>& repose_pose, std::uint64_t seed, bool trace,
                     BulletOptions options) {
  BulletRun run;
  run.step = options.step;
  const repose::RestPoseCatalog& catalog = rs.study.catalog;
  run.hist.assign(catalog.poses.size() + 1, 0);  // last bin: no rest
  const auto t_setup = Clock::now();
  BulletSide bullet(particle, options);
  run.setup_seconds = std::chrono::duration<double>(Clock::now() - t_setup).count();
  const std::uint64_t drops = repose_pose.size();
  for (std::uint64_t i = 0; i < drops; ++i) {
    const BulletSide::Drop d =
        options.toss.active
            ? bullet.drop(repose::drop_orientation(seed, i), particle.length,
                          repose::drop_toss(seed, i, rs.options.toss), TossOptions::kHeight * particle.length)
            : bullet.drop(repose::drop_orientation(seed, i), particle.length);
    run.seconds += d.seconds;
    run.mean_time += d.time / static_cast<double>(drops);
    run.depth = std::max(run.depth, d.max_depth);
    const auto [face, angle] = nearest_face(particle, d.down_body);
    const int pose = catalog.face_pose[face];
    if (trace)
      std::fprintf(
          stderr,
          "  step %.4g s, drop %llu: repose pose %d; Bullet pose %d (%.3g ms), %s at %.3f s, face %d "
          "(stability margin %.3g L) at %.3g rad\n",
          options.step, static_cast<unsigned long long>(i), repose_pose[i], pose, 1e3 * d.seconds,
          d.slept    ? "asleep"
          : d.rested ? "at rest"
                     : "NO REST",
          d.time, face, particle.face_stability_margin[face] / particle.length, angle);
    if (particle.face_stability_margin[face] <= 0 || angle > 1e-2) ++run.off_face;
    run.tilt = std::max(run.tilt, angle);
    if (d.rested) {
      ++run.hist[pose];
    } else {
      ++run.no_rest;
      ++run.hist.back();
    }
    if (repose_pose[i] == pose) ++run.agree;
  }
  return run;
}

// One shape's row; with `exported`, the row's drops and answers are appended to it (--export).
Row run_shape(const Shape& shape, std::uint64_t drops, std::uint64_t seed, bool full_settle, bool trace,
              double length, const std::vector<double>& steps, BulletOptions bullet_options,
              nlohmann::json* exported) {
  const double scale = scale_to(shape, length);
  // repose's set-up: what `repose poses` pays once per particle.
  const auto t_setup = Clock::now();
  const repose::Particle particle = make_shape_particle(shape, scale);
  ReposeSide rs = prepare_repose(particle, full_settle, bullet_options.toss);
  Row row;
  row.repose_setup_seconds = std::chrono::duration<double>(Clock::now() - t_setup).count();
  rs.options.seed = seed;
  const repose::RestPoseCatalog& catalog = rs.study.catalog;
  if (bullet_options.damping > 0) bullet_options.damping = rs.study.params.damping;
  row.name = shape.name;
  row.hull_vertices = static_cast<int>(particle.hull.vertices.size());
  row.length = particle.length;
  row.drops = drops;
  const std::size_t poses = catalog.poses.size();
  row.repose_hist.assign(poses + 1, 0);  // last bin: no rest
  for (const repose::RestPose& p : catalog.poses) row.pose_normals.push_back(p.down_normal_body);

  std::vector<int> repose_pose(drops);
  const auto t0 = Clock::now();
  for (std::uint64_t i = 0; i < drops; ++i) {
    const auto t_drop = trace ? Clock::now() : t0;
    const repose::DropOutcome outcome = repose::simulate_drop(particle, rs.landscape, catalog, rs.options, i);
    repose_pose[i] = outcome.pose;
    row.repose_steps += static_cast<std::uint64_t>(outcome.steps);
    if (trace)
      std::fprintf(stderr, "  drop %llu: repose pose %d (%.3g ms, %ld steps)\n",
                   static_cast<unsigned long long>(i), outcome.pose,
                   1e3 * std::chrono::duration<double>(Clock::now() - t_drop).count(), outcome.steps);
  }
  row.repose_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  for (int pose : repose_pose) {
    if (pose < 0) ++row.repose_no_rest;
    ++row.repose_hist[pose < 0 ? poses : static_cast<std::size_t>(pose)];
  }

  for (double step : steps) {
    bullet_options.step = step;
    row.bullet.push_back(run_bullet(particle, rs, repose_pose, seed, trace, bullet_options));
  }
  std::vector<std::vector<std::uint64_t>> hists;
  for (BulletRun& run : row.bullet) {
    run.against_finest = homogeneity(run.hist, row.bullet.back().hist);
    run.rest_against_finest = homogeneity(rest_or_not(run.hist), rest_or_not(row.bullet.back().hist));
    hists.push_back(run.hist);
  }
  row.chosen = chosen_step(hists);
  if (exported) exported->push_back(export_row(row, particle, catalog, seed, repose_pose));
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  std::uint64_t drops = 0, seed = 1;
  bool full_settle = false, histograms = true, trace = false;
  BulletOptions bullet_options;
  std::string only, mesh_list, export_file;
  double length = 0.5;  // m; 0: the shapes' own sizes
  std::string bullet_units = "auto";
  bool match_threshold = false;
  std::vector<double> steps = kCandidateSteps;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string { return i + 1 < argc ? argv[++i] : std::string(); };
    if (a == "--drops") {
      drops = std::strtoull(value().c_str(), nullptr, 10);
      if (drops == 0) return usage(argv[0]);
    } else if (a == "--seed") {
      seed = std::strtoull(value().c_str(), nullptr, 10);
    } else if (a == "--only") {
      only = ',';  // built piecewise: GCC 12's -Wrestrict misfires on "," + s + "," (GCC bug 105329)
      only += value();
      only += ',';
    } else if (a == "--full-settle") {
      full_settle = true;
    } else if (a == "--toss") {
      const std::string v = value();
      const std::size_t comma = v.find(',');
      if (comma == std::string::npos) return usage(argv[0]);
      bullet_options.toss.restitution = std::strtod(v.c_str(), nullptr);
      const std::string mu = v.substr(comma + 1);
      bullet_options.toss.friction = mu == "inf" ? INFINITY : std::strtod(mu.c_str(), nullptr);
      bullet_options.toss.active = true;
      if (!(bullet_options.toss.restitution >= 0 && bullet_options.toss.restitution <= 1) ||
          !(bullet_options.toss.friction >= 0))
        return usage(argv[0]);
    } else if (a == "--match-threshold") {
      match_threshold = true;
    } else if (a == "--bullet-units") {
      bullet_units = value();
      if (bullet_units != "m" && bullet_units != "cm" && bullet_units != "auto") return usage(argv[0]);
    } else if (a == "--meshes") {
      mesh_list = value();
    } else if (a == "--length") {
      const std::string v = value();
      length = v == "natural" ? 0 : std::strtod(v.c_str(), nullptr);
      if (!(length >= 0) || !std::isfinite(length) || (length == 0 && v != "natural")) return usage(argv[0]);
    } else if (a == "--bullet-step") {
      const double step = std::strtod(value().c_str(), nullptr);
      if (!(step > 0 && step <= 0.1)) return usage(argv[0]);
      steps = {step};
    } else if (a == "--bullet-no-sleep") {
      bullet_options.sleep = false;
    } else if (a == "--bullet-damping") {
      bullet_options.damping = 1;  // replaced by repose's C per shape
    } else if (a == "--export") {
      export_file = value();
      if (export_file.empty()) return usage(argv[0]);
    } else if (a == "--trace") {
      trace = true;
    } else if (a == "--no-histograms") {
      histograms = false;
    } else {
      return usage(argv[0], a == "--help" || a == "-h");
    }
  }
  bullet_options.units =
      bullet_units == "cm" || (bullet_units == "auto" && length > 0 && length < 0.1) ? 100.0 : 1.0;
  // Bullet's restitution velocity threshold is in its units: in m/s for repose.
  if (match_threshold)
    bullet_options.toss.threshold =
        btContactSolverInfo().m_restitutionVelocityThreshold / bullet_options.units;
  if (!export_file.empty() && bullet_options.toss.active) {
    std::fprintf(stderr, "error: --export writes drops from rest; it does not take --toss\n");
    return 2;
  }
  std::vector<std::pair<Shape, std::uint64_t>> shapes = default_shapes();
  try {
    if (!mesh_list.empty())
      for (const Shape& shape : read_mesh_list(mesh_list)) shapes.emplace_back(shape, 200);
  } catch (const repose::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  std::string steps_label;
  for (double step : steps) steps_label += (steps_label.empty() ? "" : ", ") + step_label(step);
  std::printf(
      "Bullet %d, btScalar %s precision, in %s, fixed step %s%s, margin default, deactivation %s, angular "
      "damping %s; repose %s, seed %llu; shapes at L = %s%s\n\n",
      btGetVersion(), sizeof(btScalar) == 8 ? "double" : "single",
      bullet_options.units == 100 ? "centimetres" : "metres", steps.size() > 1 ? "chosen from " : "",
      steps_label.c_str(), bullet_options.sleep ? "on" : "off",
      bullet_options.damping > 0 ? "repose's rate" : "none",
      full_settle ? "--full-settle" : "poses defaults (decide early)", static_cast<unsigned long long>(seed),
      length > 0 ? (std::to_string(length) + " m").c_str() : "their own sizes",
      bullet_options.toss.active
          ? (", tossed: E " + std::to_string(bullet_options.toss.restitution) + ", mu " +
             std::to_string(bullet_options.toss.friction) + ", repose's restitution threshold " +
             std::to_string(bullet_options.toss.threshold) + " m/s")
                .c_str()
          : "");
  std::vector<Row> rows;
  nlohmann::json exported = nlohmann::json::array();
  try {
    for (const auto& [shape, default_drops] : shapes) {
      if (!only.empty() && only.find(',' + shape.name + ',') == std::string::npos) continue;
      std::fprintf(stderr, "%s (%s) ...\n", shape.name.c_str(), shape.spec.c_str());
      rows.push_back(run_shape(shape, drops > 0 ? drops : default_drops, seed, full_settle, trace, length,
                               steps, bullet_options, export_file.empty() ? nullptr : &exported));
    }
  } catch (const repose::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  if (!export_file.empty()) {
    // Written whole to a temporary name and renamed: no partial file if the write fails.
    const std::string temporary = export_file + ".partial";
    std::ofstream out(temporary);
    out << nlohmann::json{{"seed", seed}, {"gravity", kGravity}, {"density", kDensity}, {"shapes", exported}};
    out.close();
    std::error_code error;
    if (out) std::filesystem::rename(temporary, export_file, error);
    if (!out || error) {
      std::filesystem::remove(temporary, error);
      std::fprintf(stderr, "error: %s: cannot write the export\n", export_file.c_str());
      return 1;
    }
  }
  print_table(rows);
  print_steps(rows);
  if (histograms)
    for (const Row& r : rows) print_histogram(r);
  return 0;
}
