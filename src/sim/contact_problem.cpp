// The frictional contact problem (contact_problem.hpp).
#include "contact_problem.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace repose::sim {

namespace {

// Block Gauss–Seidel sweeps: a face's 4 to 40 points converge in tens of sweeps to the tolerance; the bound
// keeps an ill-conditioned set (many nearly coincident points) finite.
constexpr int kMaxSweeps = 5000;
// Fixed-point iterations of one sliding point's direction: each contracts the angle by the ratio of the
// slip's change to the slip; the bound keeps a point whose slip ends within the impact finite.
constexpr int kMaxDirectionIterations = 100;
// Samples of the direction's angle when the fixed point does not converge; each sign change is bisected.
constexpr int kScan = 256;
constexpr int kScans = 1000000;
// A sweep that changes no point's value by more than this fraction of the scale has converged.
constexpr double kConverged = 1e-14;
// Below this fraction of the scale a value is zero (round-off).
constexpr double kTiny = 1e-14;

// What a sweep met: sliding points with no consistent normal reaction, points whose sliding direction was not
// found.
struct Counts {
  int painleve = 0;
  int unresolved = 0;
};

// The sliding reaction R = (−μλŝ, λ) of one point with x_n = 0 and ŝ the direction of its x_t with it:
// x_t(ŝ) = f_t + λ(ŝ)·(W_tn − μ·W_tt·ŝ) with λ(ŝ) = −f_n / (W_nn − μ·W_nt·ŝ) must point along ŝ. A
// fixed-point iteration from `guess` finds it in a few steps where the slip turns little; otherwise the angle
// of ŝ is scanned (kScan samples) and the sign change of ŝ × u_t bisected. With `given_normal` ≥ 0, λ is that
// (restitution) and x_n is whatever it gives.
std::optional<Vec3> sliding_reaction(const Mat3& W, const Vec3& f, double mu, double tiny, Vec2 s,
                                     double given_normal, int& scans) {
  const Eigen::Matrix2d wtt = W.topLeftCorner<2, 2>();
  const Vec2 wtn = W.block<2, 1>(0, 2), wnt = W.block<1, 2>(2, 0).transpose();
  const Vec2 ft = f.head<2>();
  const auto lambda_of = [&](const Vec2& dir) {
    return given_normal >= 0 ? given_normal : -f.z() / (W(2, 2) - mu * wnt.dot(dir));
  };
  const auto slip_of = [&](const Vec2& dir) -> Vec2 { return ft + lambda_of(dir) * (wtn - mu * wtt * dir); };
  // ŝ is consistent: λ > 0 and the slip along it (or stopped, to round-off).
  const auto consistent = [&](const Vec2& dir) {
    const double lambda = lambda_of(dir);
    if (!(lambda > 0) || !std::isfinite(lambda)) return false;
    const Vec2 ut = slip_of(dir);
    return ut.norm() <= tiny ||
           (ut.dot(dir) > 0 && std::abs(dir.x() * ut.y() - dir.y() * ut.x()) <= 1e-13 * ut.norm());
  };
  const auto impulse = [&](const Vec2& dir) {
    const double lambda = lambda_of(dir);
    return Vec3(-mu * lambda * dir.x(), -mu * lambda * dir.y(), lambda);
  };
  for (int k = 0; k < kMaxDirectionIterations; ++k) {
    if (consistent(s)) return impulse(s);
    const Vec2 ut = slip_of(s);
    if (!(lambda_of(s) > 0) || !(ut.norm() > 0)) break;
    s = ut.normalized();
  }
  // g(θ) = ŝ(θ) × u_t(ŝ(θ)), zero where the slip is along ŝ (consistent where λ > 0 and u_t·ŝ > 0).
  const auto dir = [](double theta) { return Vec2(std::cos(theta), std::sin(theta)); };
  const auto g = [&](double theta) {
    const Vec2 d = dir(theta), ut = slip_of(d);
    return d.x() * ut.y() - d.y() * ut.x();
  };
  // First a bracket near where the iteration ended (it is usually close, converging slowly), widening,
  // bisected; then the whole circle's scan.
  const auto bisect = [&](double lo, double hi, double g_lo) {
    for (int b = 0; b < 60; ++b) {
      const double mid = 0.5 * (lo + hi), g_mid = g(mid);
      ((g_mid > 0) == (g_lo > 0) ? lo : hi) = mid;
      if ((g_mid > 0) == (g_lo > 0)) g_lo = g_mid;
    }
    return dir(0.5 * (lo + hi));
  };
  if (s.allFinite() && s.norm() > 0) {
    const double centre = std::atan2(s.y(), s.x());
    for (const double half : {1e-4, 1e-2, 0.2}) {
      const double lo = centre - half, hi = centre + half;
      if (!(lambda_of(dir(lo)) > 0) || !(lambda_of(dir(hi)) > 0)) continue;
      const double g_lo = g(lo);
      if ((g_lo > 0) == (g(hi) > 0)) continue;
      const Vec2 d = bisect(lo, hi, g_lo);
      if (lambda_of(d) > 0 && (slip_of(d).dot(d) > 0 || slip_of(d).norm() <= tiny)) return impulse(d);
    }
  }
  // The whole circle's scans of a point in one solve are bounded (kScans; never reached in the tests: a
  // budget of 4 or 16 left the slip onset of a rod's foot frictionless, so the bound is only a bound).
  if (scans <= 0) return std::nullopt;
  --scans;
  const double step = 2 * 3.141592653589793 / kScan;
  for (int k = 0; k < kScan; ++k) {
    double lo = k * step, hi = lo + step;
    if (!(lambda_of(dir(lo)) > 0) || !(lambda_of(dir(hi)) > 0)) continue;
    const double g_lo = g(lo);
    if ((g_lo > 0) == (g(hi) > 0)) continue;
    const Vec2 d = bisect(lo, hi, g_lo);
    if (slip_of(d).dot(d) > 0 || slip_of(d).norm() <= tiny) return impulse(d);
  }
  return std::nullopt;  // none found (not met in the tests): the caller flags it
}

// One point's reaction given its value `f` without it (the others' reactions included) and its own block W of
// the Delassus matrix (x = f + W·R), by its rule (contact_problem.hpp).
Vec3 local_reaction(const Mat3& W, const Vec3& f, double mu, const PointCondition& c, double tiny,
                    Counts& counts, int& scans) {
  const Eigen::Matrix2d wtt = W.topLeftCorner<2, 2>();
  const Vec2 wtn = W.block<2, 1>(0, 2);
  const Vec2 ft = f.head<2>();
  if (c.rule == PointRule::sliding) {
    if (f.z() >= 0) return Vec3::Zero();
    const double d = W(2, 2) - mu * W.block<1, 2>(2, 0).dot(c.direction);
    if (!(d > 0)) {
      ++counts.painleve;
      return Vec3::Zero();
    }
    const double lambda = -f.z() / d;
    return Vec3(-mu * lambda * c.direction.x(), -mu * lambda * c.direction.y(), lambda);
  }
  const double normal = c.normal;
  if (c.rule == PointRule::unilateral) {
    if (f.z() >= 0) return Vec3::Zero();
    const Vec3 stick = -W.ldlt().solve(f);
    if (stick.z() > 0 && stick.head<2>().norm() <= mu * stick.z()) return stick;
    // Sliding: P = (−μλŝ, λ) with u_n = 0 and ŝ the direction of u_t after.
    const std::optional<Vec3> sliding = sliding_reaction(
        W, f, mu, tiny, ft.norm() > tiny ? Vec2(ft.normalized()) : Vec2(-stick.head<2>().normalized()), -1,
        scans);
    if (sliding) return *sliding;
    ++counts.unresolved;  // the frictionless plastic reaction instead
    return Vec3(0, 0, -f.z() / W(2, 2));
  }
  // The normal impulse given: the tangential one that stops the slip, if the cone allows, else sliding.
  const Vec2 stick = -wtt.ldlt().solve(ft + wtn * normal);
  if (stick.norm() <= mu * normal) return Vec3(stick.x(), stick.y(), normal);
  const std::optional<Vec3> sliding = sliding_reaction(
      W, f, mu, tiny, ft.norm() > tiny ? Vec2(ft.normalized()) : Vec2(-stick.normalized()), normal, scans);
  if (sliding) return *sliding;
  ++counts.unresolved;  // no tangential reaction instead
  return Vec3(0, 0, normal);
}

}  // namespace

Mat3 delassus_block(double mass, const Mat3& inverse_inertia, const Vec3& r) {
  Mat3 rx;
  rx << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return Mat3::Identity() / mass - rx * inverse_inertia * rx;
}

Vec3 point_value(const ContactProblem& p, std::size_t i, const Vec3& lin, const Vec3& ang) {
  Vec3 x = lin + ang.cross(p.arms[i]);
  if (!p.offsets.empty()) x += p.offsets[i];
  return x;
}

ContactSolution solve_contacts(const ContactProblem& p, const Vec3& lin, const Vec3& ang,
                               const std::vector<PointCondition>& conditions) {
  const std::size_t n = p.arms.size();
  std::vector<Mat3> diagonal(n);
  for (std::size_t i = 0; i < n; ++i) diagonal[i] = delassus_block(p.mass, p.inverse_inertia, p.arms[i]);
  const double tiny = kTiny * p.scale;
  ContactSolution s;
  s.reactions.assign(n, Vec3::Zero());
  std::vector<int> scans(n, kScans);
  s.lin = lin;
  s.ang = ang;
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    std::vector<Vec3> at_start(n);
    for (std::size_t i = 0; i < n; ++i) at_start[i] = point_value(p, i, s.lin, s.ang);
    Counts counts;
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 f = point_value(p, i, s.lin, s.ang) - diagonal[i] * s.reactions[i];
      const Vec3 next = local_reaction(diagonal[i], f, p.friction, conditions[i], tiny, counts, scans[i]);
      const Vec3 delta = next - s.reactions[i];
      s.lin += delta / p.mass;
      s.ang += p.inverse_inertia * p.arms[i].cross(delta);
      s.reactions[i] = next;
    }
    double change = 0;
    for (std::size_t i = 0; i < n; ++i)
      change = std::max(change, (point_value(p, i, s.lin, s.ang) - at_start[i]).norm());
    s.painleve = counts.painleve;
    if (change <= kConverged * p.scale) {
      s.converged = counts.unresolved == 0;
      return s;
    }
  }
  s.converged = false;
  return s;
}

}  // namespace repose::sim
