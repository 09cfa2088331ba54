// A rigid body's impact on the wall (see rigid_impact.hpp for the model).
#include "rigid_impact.hpp"

#include <algorithm>
#include <array>
#include <boost/numeric/odeint/stepper/runge_kutta_cash_karp54.hpp>
#include <cmath>

#include "../body/kinematics.hpp"
#include "../events/events.hpp"
#include "../solver/contact_problem.hpp"
#include "../tolerances.hpp"

namespace repose::sim {

namespace {

// The one direction ŝ in which sliding starts again from rest when sticking needs more than μ: the
// tangential velocity's rate K_tn − μ·K_tt·ŝ must be c·ŝ with c > 0, so ŝ = (μ·K_tt + c)⁻¹ K_tn with |ŝ| = 1;
// |ŝ(c)| falls from |K_tt⁻¹ K_tn|/μ > 1 at c = 0 to at most 1 at c = |K_tn|.
Vec2 resume_direction(const Eigen::Matrix2d& ktt, const Vec2& ktn, double mu) {
  auto s = [&](double c) { return Vec2((mu * ktt + c * Eigen::Matrix2d::Identity()).inverse() * ktn); };
  EventSearch search;
  search.max_halvings = tol::kResumeHalvings;
  search.hi_holds_known = true;
  const double hi = locate(
                        0.0, ktn.norm(), search, [&](double c) { return !(s(c).norm() > 1); }, monotone)
                        .hi;
  return s(hi).normalized();
}

// One Cash–Karp 5(4) step (Boost.Odeint) of d(P, work)/dp = (rate(P), u_n(P)) over dp from (P, work), in
// place; returns the error estimate over its tolerance (above 1: reject). The impulse's error is measured
// against tol::kImpactTolerance of the larger of the frictionless compression impulse and the impulse so far,
// the work's against that times the approach speed.
template <class Rate, class Velocity>
double embedded_step(const Rate& rate, const Velocity& velocity, Vec3& P, double& work, double dp,
                     double compression_scale, double speed) {
  using State = std::array<double, 4>;
  const auto system = [&](const State& y, State& dy, double) {
    const Vec3 at(y[0], y[1], y[2]);
    const Vec3 r = rate(at);
    dy = {r.x(), r.y(), r.z(), velocity(at).z()};
  };
  boost::numeric::odeint::runge_kutta_cash_karp54<State> stepper;
  const State in{P.x(), P.y(), P.z(), work};
  State out, error;
  stepper.do_step(system, in, 0.0, out, dp, error);
  P = Vec3(out[0], out[1], out[2]);
  work = out[3];
  const double scale = tol::kImpactTolerance * std::max(compression_scale, P.norm());
  return std::max(Vec3(error[0], error[1], error[2]).norm() / scale, std::abs(error[3]) / (scale * speed));
}

// The factor by which a step can change for its error to meet the tolerance (error: estimate over tolerance;
// the 5(4) pair's local error grows as the step's fifth power), with the usual safety factor.
double step_room(double error) {
  return error > 0 ? tol::kImpactSafety * std::pow(error, -1.0 / tol::kImpactErrorOrder) : INFINITY;
}

Motion apply(double mass, const Mat3& inverse_inertia, const Vec3& r, const Motion& m, const Vec3& impulse) {
  return {m.velocity + impulse / mass, m.omega + inverse_inertia * r.cross(impulse)};
}

}  // namespace

ImpactOutcome collide(double mass, const Mat3& inertia, const Vec3& r, const Motion& before,
                      const ImpactLaw& law) {
  ImpactOutcome out;
  out.after = before;
  const Vec3 u0 = point_velocity(before.velocity, before.omega, r);
  out.speed_before = out.speed_after = u0;
  out.stick = u0.head<2>().norm() == 0;
  if (!(u0.z() < 0)) return out;

  const Mat3 inverse = inertia.inverse();
  const Mat3 K = delassus_block(mass, inverse, r);
  const Eigen::Matrix2d ktt = K.topLeftCorner<2, 2>();
  const Vec2 ktn = K.block<2, 1>(0, 2);
  const Vec2 stuck_rate = -ktt.ldlt().solve(ktn);  // dP_t/dp that keeps a stuck point stuck
  const double e = law.restitution, mu = law.friction;
  const double u_tiny = tol::kTinySpeed * u0.norm();  // speeds below this are zero (round-off of u0)
  // A slip below tol::kImpactStoppedSlip of the approach speed has stopped: stick, or slide the other way.
  const double stop_speed = std::max(u_tiny, tol::kImpactStoppedSlip * u0.norm());
  const double compression_scale = -u0.z() / K(2, 2);  // the frictionless compression impulse
  // The normal impulse that stops the initial slip at the slowest (K_tt is symmetric positive definite: its
  // smaller eigenvalue in closed form).
  const double ktt_min = 0.5 * (ktt(0, 0) + ktt(1, 1)) - std::hypot(0.5 * (ktt(0, 0) - ktt(1, 1)), ktt(0, 1));
  const double slip_scale =
      mu > 0 && std::isfinite(mu) && ktt_min > 0 ? u0.head<2>().norm() / (mu * ktt_min) : 0.0;

  auto velocity = [&](const Vec3& P) { return Vec3(u0 + K * P); };
  Vec3 P = Vec3::Zero();
  double work = 0;  // of the normal impulse, ∫ u_n dp
  bool restitution = false, done = false;
  double target = 0;  // the work at which restitution ends
  auto end_compression = [&] {
    restitution = true;
    target = (1 - e * e) * work;
    done = e == 0;
  };
  bool sticking = std::isinf(mu);
  if (sticking) P.head<2>() = -ktt.ldlt().solve(u0.head<2>());  // no slip: sliding stops at once
  bool resumed = false;
  Vec2 resume = Vec2::Zero();
  double cap = INFINITY;  // the longest step, halved where a step overshot the end of separation
  double h = compression_scale / tol::kImpactFirstSteps;  // the error control's step

  for (int step = 0; !done; ++step) {
    if (step ==
        tol::kImpactMaxSteps) {  // not ended (see tol::kImpactMaxSteps): the frictionless law, flagged
      const Vec3 impulse(0, 0, (1 + e) * compression_scale);
      out.after = apply(mass, inverse, r, before, impulse);
      out.impulse = impulse;
      out.speed_after = velocity(impulse);
      out.stick = false;
      out.fallback = true;
      return out;
    }
    const Vec3 u = velocity(P);
    if (sticking) {
      // Everything is linear from here: the point stays stuck (K is constant during the impact).
      const Vec3 rate = K * Vec3(stuck_rate.x(), stuck_rate.y(), 1);  // du/dp, rate.z() > 0 (Schur)
      double un = u.z();
      if (!restitution) {
        const double dp = std::max(0.0, -un / rate.z());
        work += un * dp + 0.5 * rate.z() * dp * dp;
        P += dp * Vec3(stuck_rate.x(), stuck_rate.y(), 1);
        un = 0;
        end_compression();
        if (done) break;
      }
      const double need = std::max(0.0, target - work);
      const double dp = (-un + std::sqrt(un * un + 2 * rate.z() * need)) / rate.z();
      work += un * dp + 0.5 * rate.z() * dp * dp;
      P += dp * Vec3(stuck_rate.x(), stuck_rate.y(), 1);
      break;
    }
    const Vec2 ut = u.head<2>();
    const double slide = ut.norm();
    if (mu > 0 && slide <= stop_speed && !resumed) {  // sliding has stopped: stick, or slide the other way
      if (stuck_rate.norm() <= mu) {
        sticking = true;
        continue;
      }
      resume = resume_direction(ktt, ktn, mu);
      resumed = true;
    }
    const Vec2 s0 = slide > u_tiny ? Vec2(ut / slide) : resume;
    auto rate = [&](const Vec3& at) {  // dP/dp
      // Slipping again from a stop, the point slides along the direction whose slip grows along itself:
      // the rates are constant (a slip of round-off size has no direction of its own).
      if (resumed) return Vec3(-mu * s0.x(), -mu * s0.y(), 1);
      const Vec2 t = velocity(at).head<2>();
      const Vec2 s = t.norm() > u_tiny ? Vec2(t.normalized()) : s0;
      return Vec3(-mu * s.x(), -mu * s.y(), 1);
    };
    const Vec3 dP = rate(P);
    const Vec3 du = K * dP;
    // The step: the error control's, and no further than the first event on the rates at its start (exact
    // when the sliding direction does not turn: the rates are constant, no error, and the step reaches it).
    double dp = std::min(h, cap);
    enum { none, stops, compressed, finished } event = none;
    const double slowing = s0.dot(du.head<2>());
    // Near a slip of zero the direction turns through a finite angle within an impulse of the order of the
    // slip itself: in 3-D a slip generally passes by zero, swinging round, or stops along a direction it has
    // settled on. A step that jumps to the stop its rates predict while the direction still turns, or that
    // steps over the swing, integrates it to first order only (before: errors of 1e-3 to 0.4 of the impulse
    // in 0.5 % of random impacts). So a step changes the slip by at most tol::kImpactSlipChangePerStep of
    // itself (its turn is the error control's), and the jump to a stop waits for the turn over it to fall
    // below tol::kImpactStopTurn (or for the stop to be within tol::kImpactStopReach of the impulse scale: a
    // slip that hovers near zero, its direction circling, is stuck in fact).
    bool may_stop = true;
    if (slide > u_tiny) {
      const double across = (du.head<2>() - slowing * s0).norm();
      may_stop = slowing < 0 &&
                 (across <= tol::kImpactStopTurn * -slowing ||
                  slide / -slowing <= tol::kImpactStopReach * std::max(compression_scale, slip_scale));
      if (!may_stop) dp = std::min(dp, tol::kImpactSlipChangePerStep * slide / du.head<2>().norm());
    }
    if (mu > 0 && slide > u_tiny && slowing < 0 && may_stop && slide / -slowing <= dp) {
      dp = slide / -slowing;
      event = stops;
    }
    if (!restitution && du.z() > 0 && -u.z() / du.z() <= dp) {
      dp = -u.z() / du.z();
      event = compressed;
    }
    if (restitution) {
      // The impulse at which the work b·Δ + ½·a·Δ² reaches `need` (the smaller root); where the normal
      // velocity falls too fast for that (a < 0, friction), where it reaches zero: no more work can be done.
      const double need = std::max(0.0, target - work);
      const double a = du.z(), b = std::max(u.z(), 0.0);
      const double discriminant = b * b + 2 * a * need;
      // Nothing left to do (a grazing impact whose compression did no work) ends at once, not at 0/0.
      const double to_end = need <= 0 ? 0.0
                            : discriminant >= 0 && (a != 0 || b > 0)
                                ? need / (0.5 * (b + std::sqrt(discriminant)))
                            : a < 0 ? b / -a
                                    : INFINITY;
      if (to_end <= dp) {
        dp = to_end;
        event = finished;
      }
    }
    const Vec3 P_start = P;
    const double work_start = work;
    // One embedded Runge–Kutta step on (P, work) over dp; a step whose error estimate exceeds the tolerance
    // is taken again, shorter (its event, predicted anew).
    const auto take = [&](double d) {
      P = P_start;
      work = work_start;
      return embedded_step(rate, velocity, P, work, d, compression_scale, u0.norm());
    };
    double error = take(dp);
    // A step onto the end of compression or of restitution, predicted on the rates at its start, overshoots
    // it where the sliding direction turns within the step: it is taken again, shortened by Newton's step on
    // the normal velocity (the work), until it lands within the tolerance. (Short of it, the next step goes
    // on.)
    for (int k = 0; k < tol::kImpactEventIterations && error <= 1 && event != none && event != stops; ++k) {
      const double over = event == compressed ? velocity(P).z() : work - target;
      const double slope = event == compressed ? (K * rate(P)).z() : velocity(P).z();
      const double allowed =
          tol::kImpactTolerance * u0.norm() * (event == compressed ? 1 : compression_scale);
      if (!(over > allowed && slope > 0 && over / slope < dp)) break;
      dp -= over / slope;
      error = take(dp);
    }
    if (error > 1) {
      P = P_start;
      work = work_start;
      h = dp * std::max(tol::kImpactShrinkMin, step_room(error));
      continue;
    }
    // The next step grows with the error's room, from the step the control allowed (a step cut short by an
    // event or the slip's change does not shrink the next).
    if (dp >= h) h = dp * std::min(tol::kImpactGrowMax, step_room(error));
    if (event == finished && velocity(P).z() < -u_tiny) {
      // The point's normal velocity fell through zero within the step (the direction turned): the step is
      // taken again, halved, so that restitution ends where separation ends, not beyond it.
      P = P_start;
      work = work_start;
      cap = 0.5 * dp;
      continue;
    }
    resumed = resumed && event != stops;
    switch (event) {
      case stops:
        // Stopped, up to the turning of the direction within the step: a remainder at round-off level is
        // removed (within the cone: it is that small); a larger one is slid out by the next steps.
        if (velocity(P).head<2>().norm() <= tol::kStopFraction * slide) {
          P.head<2>() -= ktt.ldlt().solve(velocity(P).head<2>());
          resumed = false;
        }
        break;
      case compressed:
        if (velocity(P).z() >= -u_tiny) end_compression();
        break;
      case finished:
        // The step was predicted on the rates at its start: where the sliding direction turned within it,
        // the work may still fall short of the target, and restitution goes on (a shorter step each time).
        // It ends when the target is met, when the point no longer separates (no more work can be done), or
        // when what is left is round-off.
        done = work >= target - tol::kEnergyMet * std::abs(target) || !(velocity(P).z() > 0) ||
               dp <= tol::kImpactNegligibleStep * P.z();
        break;
      case none:
        break;
    }
    if (!restitution && velocity(P).z() >= 0) end_compression();
  }
  out.impulse = P;
  out.after = apply(mass, inverse, r, before, P);
  out.speed_after = velocity(P);
  out.stick = sticking || out.speed_after.head<2>().norm() <= u_tiny;
  return out;
}

std::optional<Vec3> impulse_centre(double mass, const Mat3& inertia, const std::vector<Vec3>& r,
                                   const Motion& before) {
  const std::size_t n = r.size();
  const Mat3 inverse = inertia.inverse();
  std::vector<Vec3> arm(n);  // r_i × ẑ: the rotation a unit normal impulse at point i causes, times I
  std::vector<double> b(n), x(n, 0.0);
  double scale = 0;
  for (std::size_t i = 0; i < n; ++i) {
    arm[i] = r[i].cross(Vec3::UnitZ());
    b[i] = (point_velocity(before.velocity, before.omega, r[i])).z();
    scale = std::max(scale, std::abs(b[i]));
  }
  Eigen::MatrixXd A(n, n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) A(i, j) = 1 / mass + arm[i].dot(inverse * arm[j]);
  // Projected Gauss–Seidel on: x ≥ 0, w = A·x + b ≥ 0, x·w = 0 (A is positive semi-definite, so it converges
  // to a solution; every solution gives the same velocities, hence the same resultant and centre).
  for (int sweep = 0; sweep < tol::kImpulseCentreSweeps; ++sweep) {
    double change = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double w =
          b[i] + A.row(static_cast<Eigen::Index>(i)).dot(Eigen::Map<const Eigen::VectorXd>(x.data(), n));
      const double xi = std::max(0.0, x[i] - w / A(i, i));
      change = std::max(change, std::abs(xi - x[i]) / mass);
      x[i] = xi;
    }
    if (change <= tol::kSweepChange * scale) break;
  }
  double total = 0;
  Vec3 centre = Vec3::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    total += x[i];
    centre += x[i] * r[i];
  }
  if (!(total > 0)) return std::nullopt;
  return centre / total;
}

}  // namespace repose::sim
