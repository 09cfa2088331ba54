// Several points striking the wall at once (multi_impact.hpp).
#include "multi_impact.hpp"

#include <algorithm>
#include <cmath>

#include "tolerances.hpp"

namespace repose::sim {

namespace {

// Block Gauss–Seidel sweeps: a face's 4 to 40 points converge in tens of sweeps to the tolerance; the bound
// keeps an ill-conditioned set (many nearly coincident points) finite.
constexpr int kMaxSweeps = 5000;
// Fixed-point iterations of one sliding point's direction: each contracts the angle by the ratio of the
// slip's change to the slip; the bound keeps a point whose slip ends within the impact finite.
constexpr int kMaxDirectionIterations = 100;
constexpr int kScan = 256;
// A sweep that changes no point's velocity by more than this fraction of the fastest has converged.
constexpr double kConverged = 1e-14;
// Halvings of the restitution's scale when Poisson's rule with friction would raise the energy.
constexpr int kMaxScaleHalvings = 60;

Mat3 skew(const Vec3& a) {
  Mat3 m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

// The sliding impulse P = (−μλŝ, λ) of one point with u_n = 0 after and ŝ the direction of its slip after:
// u_t(ŝ) = f_t + λ(ŝ)·(W_tn − μ·W_tt·ŝ) with λ(ŝ) = −f_n / (W_nn − μ·W_nt·ŝ) must point along ŝ. A
// fixed-point iteration from `guess` finds it in a few steps where the slip turns little; otherwise the angle
// of ŝ is scanned (kScan samples) and the sign change of ŝ × u_t bisected.
Vec3 sliding_impulse(const Mat3& W, const Vec3& f, double mu, double tiny, Vec2 s) {
  const Eigen::Matrix2d wtt = W.topLeftCorner<2, 2>();
  const Vec2 wtn = W.block<2, 1>(0, 2), wnt = W.block<1, 2>(2, 0).transpose();
  const Vec2 ft = f.head<2>();
  const auto lambda_of = [&](const Vec2& dir) { return -f.z() / (W(2, 2) - mu * wnt.dot(dir)); };
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
  // The scan: g(θ) = ŝ(θ) × u_t(ŝ(θ)), where λ > 0 and u_t·ŝ > 0.
  const auto dir = [](double theta) { return Vec2(std::cos(theta), std::sin(theta)); };
  const auto g = [&](double theta) {
    const Vec2 d = dir(theta), ut = slip_of(d);
    return d.x() * ut.y() - d.y() * ut.x();
  };
  const double step = 2 * 3.141592653589793 / kScan;
  for (int k = 0; k < kScan; ++k) {
    double lo = k * step, hi = lo + step;
    if (!(lambda_of(dir(lo)) > 0) || !(lambda_of(dir(hi)) > 0)) continue;
    double g_lo = g(lo);
    if ((g_lo > 0) == (g(hi) > 0)) continue;
    for (int b = 0; b < 60; ++b) {
      const double mid = 0.5 * (lo + hi), g_mid = g(mid);
      ((g_mid > 0) == (g_lo > 0) ? lo : hi) = mid;
      if ((g_mid > 0) == (g_lo > 0)) g_lo = g_mid;
    }
    const Vec2 d = dir(0.5 * (lo + hi));
    if (slip_of(d).dot(d) > 0 || slip_of(d).norm() <= tiny) return impulse(d);
  }
  return Vec3(0, 0, -f.z() / W(2, 2));  // none (not met in the tests): frictionless
}

// One point's impulse given its velocity `f` without it (the others' impulses included) and its own block
// W of the Delassus matrix (u = f + W·P). With `normal` ≥ 0 the normal impulse is that (restitution);
// otherwise it is the plastic one (u_n = 0 if the point approaches, else no impulse).
Vec3 local_impulse(const Mat3& W, const Vec3& f, double mu, double normal, double tiny) {
  const Eigen::Matrix2d wtt = W.topLeftCorner<2, 2>();
  const Vec2 wtn = W.block<2, 1>(0, 2);
  const Vec2 ft = f.head<2>();
  if (normal < 0) {
    if (f.z() >= 0) return Vec3::Zero();
    const Vec3 stick = -W.ldlt().solve(f);
    if (stick.z() > 0 && stick.head<2>().norm() <= mu * stick.z()) return stick;
    // Sliding: P = (−μλŝ, λ) with u_n = 0 and ŝ the direction of u_t after.
    return sliding_impulse(W, f, mu, tiny,
                           ft.norm() > tiny ? Vec2(ft.normalized()) : Vec2(-stick.head<2>().normalized()));
  }
  // The normal impulse given: the tangential one that stops the slip, if the cone allows, else sliding.
  const Vec2 stick = -wtt.ldlt().solve(ft + wtn * normal);
  if (stick.norm() <= mu * normal) return Vec3(stick.x(), stick.y(), normal);
  Vec2 s = ft.norm() > tiny ? Vec2(ft.normalized()) : Vec2(-stick.normalized());
  for (int k = 0; k < kMaxDirectionIterations; ++k) {
    const Vec2 ut = ft + wtn * normal - mu * normal * (wtt * s);
    if (ut.norm() <= tiny) break;
    const Vec2 next = ut.normalized();
    const bool settled = (next - s).norm() <= 1e-15;
    s = next;
    if (settled) break;
  }
  return Vec3(-mu * normal * s.x(), -mu * normal * s.y(), normal);
}

}  // namespace

MultiImpactOutcome collide_points(double mass, const Mat3& inertia, const std::vector<Vec3>& arms,
                                  const Motion& before, const ImpactLaw& law) {
  const std::size_t n = arms.size();
  const Mat3 inverse = inertia.inverse();
  std::vector<Mat3> rx(n);
  for (std::size_t i = 0; i < n; ++i) rx[i] = skew(arms[i]);
  // The Delassus blocks: a unit impulse at j changes point i's velocity by W_ij.
  const auto W = [&](std::size_t i, std::size_t j) -> Mat3 {
    return Mat3::Identity() / mass - rx[i] * inverse * rx[j];
  };
  std::vector<Mat3> diagonal(n);
  for (std::size_t i = 0; i < n; ++i) diagonal[i] = W(i, i);

  const auto apply = [&](const Motion& m, const std::vector<Vec3>& P) {
    Motion out = m;
    for (std::size_t i = 0; i < n; ++i) {
      out.velocity += P[i] / mass;
      out.omega += inverse * arms[i].cross(P[i]);
    }
    return out;
  };
  const auto point_velocity = [&](const Motion& m, std::size_t i) -> Vec3 {
    return m.velocity + m.omega.cross(arms[i]);
  };
  double speed = 0;
  for (std::size_t i = 0; i < n; ++i) speed = std::max(speed, point_velocity(before, i).norm());
  const double tiny = tol::kTinySpeed * speed;

  MultiImpactOutcome out;
  // Gauss–Seidel on the impulses P from the motion `start`; `normal` (if not empty) fixes the normal ones.
  const auto solve = [&](const Motion& start, const std::vector<double>& normal) {
    std::vector<Vec3> P(n, Vec3::Zero());
    Motion m = start;
    for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
      // Converged when a sweep no longer changes any point's velocity: the motion is then determined even
      // where the impulses are not (four corners of a face share three constraints).
      const Motion at_start = m;
      for (std::size_t i = 0; i < n; ++i) {
        // This point's velocity without its own impulse.
        const Vec3 f = point_velocity(m, i) - diagonal[i] * P[i];
        const Vec3 next =
            local_impulse(diagonal[i], f, law.friction, normal.empty() ? -1.0 : normal[i], tiny);
        const Vec3 delta = next - P[i];
        m.velocity += delta / mass;
        m.omega += inverse * arms[i].cross(delta);
        P[i] = next;
      }
      double change = 0;
      for (std::size_t i = 0; i < n; ++i)
        change = std::max(change, (point_velocity(m, i) - point_velocity(at_start, i)).norm());
      if (change <= kConverged * speed) return P;
    }
    out.converged = false;
    return P;
  };

  const std::vector<Vec3> compression = solve(before, {});
  const Motion compressed = apply(before, compression);
  std::vector<Vec3> total = compression;
  Motion after = compressed;
  if (law.restitution > 0) {
    std::vector<double> normal(n);
    for (std::size_t i = 0; i < n; ++i) normal[i] = law.restitution * compression[i].z();
    const std::vector<Vec3> restitution = solve(compressed, normal);
    const double limit = kinetic_energy(mass, inertia, before);
    double scale = 1;
    std::vector<Vec3> scaled = restitution;
    for (int k = 0; k < kMaxScaleHalvings; ++k) {
      for (std::size_t i = 0; i < n; ++i) scaled[i] = scale * restitution[i];
      if (kinetic_energy(mass, inertia, apply(compressed, scaled)) <= limit) break;
      scale *= 0.5;
    }
    if (kinetic_energy(mass, inertia, apply(compressed, scaled)) > limit) scaled.assign(n, Vec3::Zero());
    for (std::size_t i = 0; i < n; ++i) total[i] += scaled[i];
    after = apply(compressed, scaled);
  }
  out.after = after;
  out.impulses = total;
  out.speed_after.resize(n);
  for (std::size_t i = 0; i < n; ++i) out.speed_after[i] = point_velocity(after, i);
  return out;
}

}  // namespace repose::sim
