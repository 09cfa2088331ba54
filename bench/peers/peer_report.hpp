// The peer benchmark's results (peer_bullet.cpp): per shape, repose's and Bullet's (at each step) rest poses
// and costs, and the tables printed from them.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <repose/geometry/types.hpp>
#include <string>
#include <vector>

#include "bullet_steps.hpp"

namespace peer {

// Bullet's answer at one step.
struct BulletRun {
  double step = 0;
  double seconds = 0, setup_seconds = 0;
  double depth = -INFINITY, mean_time = 0, tilt = 0;
  std::uint64_t no_rest = 0, off_face = 0, agree = 0;
  std::vector<std::uint64_t> hist;
  Homogeneity against_finest;       // its histogram against the finest step's
  Homogeneity rest_against_finest;  // its drops at rest or not against the finest step's
};

struct Row {
  std::string name;
  int hull_vertices = 0;
  double length = 0;
  std::uint64_t drops = 0;
  double repose_seconds = 0, repose_setup_seconds = 0;
  std::uint64_t repose_steps = 0;  // the engine's steps over all drops (outcome.steps)
  std::uint64_t repose_no_rest = 0;
  std::vector<std::uint64_t> repose_hist;
  std::vector<Vec3> pose_normals;
  std::vector<BulletRun> bullet;  // one per step, coarsest first
  std::size_t chosen = 0;         // Bullet's step: its cheapest trustworthy one
  const BulletRun& best() const { return bullet[chosen]; }
};

// A step as the fraction it is (1/60 s), or in seconds if it is none of them.
std::string step_label(double step) {
  const double inverse = 1 / step;
  if (std::abs(inverse - std::round(inverse)) < 1e-9 * inverse)
    return "1/" + std::to_string(std::lround(inverse)) + " s";
  return std::to_string(step) + " s";
}

void print_histogram(const Row& row) {
  std::printf(
      "\n%s: rest poses (repose catalogue; Bullet's final down direction -> nearest hull face -> its "
      "pose), Bullet at each step\n\n| pose | down normal (body) | repose |",
      row.name.c_str());
  for (const BulletRun& run : row.bullet) std::printf(" Bullet %s |", step_label(run.step).c_str());
  std::printf("\n|---:|---|---:|");
  for (std::size_t k = 0; k < row.bullet.size(); ++k) std::printf("---:|");
  std::printf("\n");
  const auto total = [&](std::size_t p) {
    std::uint64_t n = row.repose_hist[p];
    for (const BulletRun& run : row.bullet) n += run.hist[p];
    return n;
  };
  std::vector<std::size_t> order;
  for (std::size_t p = 0; p < row.pose_normals.size(); ++p)
    if (total(p) > 0) order.push_back(p);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return total(a) > total(b); });
  order.push_back(row.pose_normals.size());  // no rest, last
  for (std::size_t p : order) {
    if (p == row.pose_normals.size()) {
      if (total(p) == 0) break;
      std::printf("| no rest | | %llu |", static_cast<unsigned long long>(row.repose_hist[p]));
    } else {
      const Vec3& n = row.pose_normals[p];
      std::printf("| %zu | (%+.3f, %+.3f, %+.3f) | %llu |", p, n.x(), n.y(), n.z(),
                  static_cast<unsigned long long>(row.repose_hist[p]));
    }
    for (const BulletRun& run : row.bullet)
      std::printf(" %llu |", static_cast<unsigned long long>(run.hist[p]));
    std::printf("\n");
  }
  std::printf(
      "\nsame pose in both engines (Bullet at %s): %llu of %llu drops; Bullet's largest angle between its "
      "final down direction and the nearest hull face normal: %.2g rad\n",
      step_label(row.best().step).c_str(), static_cast<unsigned long long>(row.best().agree),
      static_cast<unsigned long long>(row.drops), row.best().tilt);
}

// Per shape and step: Bullet's cost and its agreement with its finest step.
void print_steps(const std::vector<Row>& rows) {
  std::printf(
      "\nBullet's step per shape: its rest-pose histogram against its finest step's (Pearson chi-square "
      "homogeneity by permutation; the chosen step is the largest with p >= %.2f)\n\n",
      kAgreementLevel);
  std::printf(
      "| shape | step | Bullet ms/settle | simulated s/settle | max depth of a hull vertex (L) | no rest | "
      "off a "
      "stable face | chi-square (bins) | p | p, at rest or not | chosen |\n"
      "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
  for (const Row& r : rows)
    for (std::size_t k = 0; k < r.bullet.size(); ++k) {
      const BulletRun& b = r.bullet[k];
      std::printf("| %s | %s | %.3f | %.2f | %.1e | %llu | %llu | %.1f (%d) | %.3g | %.3g | %s |\n",
                  r.name.c_str(), step_label(b.step).c_str(), 1e3 * b.seconds / static_cast<double>(r.drops),
                  b.mean_time, std::max(0.0, b.depth) / r.length, static_cast<unsigned long long>(b.no_rest),
                  static_cast<unsigned long long>(b.off_face), b.against_finest.chi2, b.against_finest.bins,
                  b.against_finest.p, b.rest_against_finest.p, k == r.chosen ? "yes" : "");
    }
}

void print_table(const std::vector<Row>& rows) {
  std::printf(
      "| shape | hull vertices | L (m) | drops | repose ms/settle | repose steps/settle | repose µs/step | "
      "repose set-up ms | Bullet step | Bullet ms/settle | Bullet steps/settle | Bullet µs/step | Bullet / "
      "repose | Bullet / repose, 1,000 drops with set-up | Bullet / repose at 1 ms | Bullet simulated "
      "s/settle | Bullet max depth of a hull vertex (L) | same pose | Bullet no rest / off a stable face "
      "|\n");
  std::printf(
      "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const Row& r : rows) {
    const double n = static_cast<double>(r.drops);
    const BulletRun& b = r.best();
    const double rep = r.repose_seconds / n, bul = b.seconds / n;
    const double whole = (b.setup_seconds + 1000 * bul) / (r.repose_setup_seconds + 1000 * rep);
    std::string at_1ms = "—";
    for (const BulletRun& run : r.bullet)
      if (run.step == 1e-3) {
        char ratio[32];
        std::snprintf(ratio, sizeof ratio, "%.2f", run.seconds / n / rep);
        at_1ms = ratio;
      }
    // Steps: repose's engine steps (events and integrator steps alike); Bullet's fixed steps, its simulated
    // time over its step.
    const double repose_steps = static_cast<double>(r.repose_steps) / n, bullet_steps = b.mean_time / b.step;
    std::printf(
        "| %s | %d | %.3f | %llu | %.3f | %.1f | %.2f | %.1f | %s | %.3f | %.1f | %.2f | %.2f | %.2f | %s | "
        "%.2f | %.1e | %.0f %% | %llu / %llu |\n",
        r.name.c_str(), r.hull_vertices, r.length, static_cast<unsigned long long>(r.drops), 1e3 * rep,
        repose_steps, 1e6 * rep / std::max(repose_steps, 1.0), 1e3 * r.repose_setup_seconds,
        step_label(b.step).c_str(), 1e3 * bul, bullet_steps, 1e6 * bul / std::max(bullet_steps, 1.0),
        bul / rep, whole, at_1ms.c_str(), b.mean_time, std::max(0.0, b.depth) / r.length,
        100.0 * static_cast<double>(b.agree) / n, static_cast<unsigned long long>(b.no_rest),
        static_cast<unsigned long long>(b.off_face));
  }
}

}  // namespace peer
