// Off the wall: the free fall (section 2.1) and, for a toss or a rebound, the flight (issue 14). The centre
// of mass follows its parabola exactly; the orientation is fixed (no spin: the touch time in closed form) or
// turns torque-free (Euler's equations, integrated to the engine's tolerance), its touch found on the dense
// output by a search that cannot step over it.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include "settler.hpp"

namespace repose {

namespace {
constexpr int kTouchBisections = 44;   // a touch is bracketed to 2^-44 of a step (as every event)
constexpr int kTouchIntervals = 4096;  // bound on the intervals the touch search examines in one step
}  // namespace

Vec3 Settler::Impl::flight_velocity() const {
  return fall_velocity - Vec3(0, 0, params.gravity * (t - fall_t0));
}

// Starts a flight at t from the current pose with the given velocities; `height` is the lowest point's
// height above the wall (the caller's exact value: the drop height, or 0 after a rebound).
void Settler::Impl::begin_flight(const Vec3& velocity, const Vec3& omega, double height) {
  falling = true;
  fall_origin = com;
  fall_velocity = velocity;
  fall_t0 = t;
  fall_steps = 0;
  flight_omega = omega;
  spinning = omega != Vec3::Zero();
  const bool first = phases.empty();
  set_type(first && !spinning ? ContactType::free_fall : ContactType::flight);
  if (!spinning) {
    lowest_body_height = INFINITY;
    for (const Vec3& v : particle.hull.vertices)
      lowest_body_height = std::min(lowest_body_height, (q * v).z());
    const double up = velocity.z(), g = params.gravity;
    touch_time = fall_t0 + (up + std::sqrt(up * up + 2 * g * height)) / g;
    return;
  }
  if (!flight_rotation) {
    free_body = {body.mass, body.inertia, body.gravity, 0.0};
    flight_rotation.emplace(free_body, length, params.tolerance,
                            kAdaptiveMaxStep * std::sqrt(length / params.gravity));
  }
  const sim::Support centre{com, Vec3::Zero(), false, Vec3::UnitX()};
  const Mat3 R = q.toRotationMatrix();
  const Vec3 momentum = R * body.inertia * R.transpose() * omega;  // about the centre of mass
  flight_rotation->start(centre, {q, omega, momentum}, t, kFirstStep * std::sqrt(length / params.gravity));
  flight_step_end = t;
  flight_touch = INFINITY;
}

// A flight without rotation, exact: the parabola from its start, to the touch time found in closed form.
// Steps end on the grid of multiples of dt from the flight's start (observers see the fall there); a stop at
// the time limit or at advance_to() is not a step, so where a run is stopped never changes it.
void Settler::Impl::fall_step() {
  if (spinning) {
    spin_step();
    return;
  }
  const double g = params.gravity, down = -fall_velocity.z();
  const double grid = fall_t0 + static_cast<double>(fall_steps + 1) * dt;
  const double end = std::min({grid, touch_time, max_time, limit});
  t = end;
  const double tau = t - fall_t0;
  com.x() = fall_origin.x() + fall_velocity.x() * tau;
  com.y() = fall_origin.y() + fall_velocity.y() * tau;
  if (end == touch_time) {
    ++steps;
    com.z() = -lowest_body_height;  // exactly touching
    touch(flight_velocity(), Vec3::Zero());
    return;
  }
  if (end == grid) {
    ++fall_steps;
    ++steps;
  }
  com.z() = fall_origin.z() - (down * tau + 0.5 * g * tau * tau);
}

// A flight with rotation: one integrator step at a time, the touch located in each before the flight goes on.
void Settler::Impl::spin_step() {
  if (t >= flight_step_end) {
    const auto [a, b] = flight_rotation->step();
    flight_step_end = b;
    flight_touch = locate_touch(a, b);
    ++steps;
  }
  const double end = std::min({flight_touch, flight_step_end, max_time, limit});
  t = end;
  const sim::Rotation state = flight_rotation->state_at(t);
  q = state.q;
  flight_omega = state.omega;
  const double tau = t - fall_t0;
  com = fall_origin + fall_velocity * tau - Vec3(0, 0, 0.5 * params.gravity * tau * tau);
  if (end != flight_touch) return;
  // The bracket's lower end has every vertex on or above the wall: the lowest is set exactly on it.
  double lowest = INFINITY;
  for (const Vec3& v : particle.hull.vertices) lowest = std::min(lowest, (q * v).z());
  com.z() = -lowest;
  touch(flight_velocity(), flight_omega);
}

// The first instant in (a, b] at which a hull vertex reaches the wall, or +∞: the lower end of a bracket
// 2^-44 of the step wide, so nothing is ever below the wall. The search cannot step over a touch: over an
// interval [s0, s1] a vertex's height z has |z''| ≤ A = g + 2·R·|L|²/I_min² (the centre of mass's fall plus
// the body's centripetal and torque-free angular accelerations, |ω| ≤ |L|/I_min), so from z and z' at both
// ends it stays above the wall for (z'(s0) + sqrt(z'(s0)² + 2·A·z(s0)))/A after s0 and the mirror time
// before s1; an interval those two cover is clear, any other is halved, earliest first.
double Settler::Impl::locate_touch(double a, double b) {
  const auto& verts = particle.hull.vertices;
  if (flight_inertia_min == 0)
    flight_inertia_min =
        Eigen::SelfAdjointEigenSolver<Mat3>(body.inertia, Eigen::EigenvaluesOnly).eigenvalues().minCoeff();
  const double i_min = flight_inertia_min;
  const Mat3 R0 = q.toRotationMatrix();
  const double spin_momentum = (R0 * body.inertia * R0.transpose() * flight_omega).norm();
  const double accel = params.gravity + 2 * hull_radius * spin_momentum * spin_momentum / (i_min * i_min);
  // The centre of mass's height and vertical speed at instant s (its parabola), and a vertex's on top of
  // them.
  const auto centre = [&](double s) {
    const double tau = s - fall_t0;
    return std::pair{fall_origin.z() + fall_velocity.z() * tau - 0.5 * params.gravity * tau * tau,
                     fall_velocity.z() - params.gravity * tau};
  };
  const auto vertex = [&](const sim::Rotation& st, std::pair<double, double> c, std::size_t k) {
    const Vec3 r = st.q * verts[k];
    return std::pair{c.first + r.z(), c.second + st.omega.cross(r).z()};
  };
  // Whether a vertex at heights zl, zr ≥ 0 (round-off clamped) and speeds vl, vr at tl, tr stays above the
  // wall in between, by the bound A.
  const auto vertex_clear = [&](double tl, double zl, double vl, double tr, double zr, double vr) {
    zl = std::max(zl, 0.0);
    zr = std::max(zr, 0.0);
    const double after = (vl + std::sqrt(vl * vl + 2 * accel * zl)) / accel;
    const double before = (-vr + std::sqrt(vr * vr + 2 * accel * zr)) / accel;
    return after + before >= tr - tl;
  };
  // The vertices that may reach the wall in (a, b]: every other one stays above it over the whole step by the
  // bound, hence over each part of it, so the search looks at these only (a body rolling on its rim has a
  // handful near the wall among hundreds).
  touch_candidates.clear();
  {
    const sim::Rotation sa = flight_rotation->state_at(a), sb = flight_rotation->state_at(b);
    const auto ca = centre(a), cb = centre(b);
    for (std::size_t k = 0; k < verts.size(); ++k) {
      const auto [za, va] = vertex(sa, ca, k);
      const auto [zb, vb] = vertex(sb, cb, k);
      if (zb < 0 || !vertex_clear(a, za, va, b, zb, vb)) touch_candidates.push_back(k);
    }
  }
  if (touch_candidates.empty()) return INFINITY;
  // The candidates' heights and vertical speeds at an instant: recomputed from the instant when needed, not
  // kept with the intervals still to examine (a wide search keeps thousands of intervals). The last few are
  // cached, since the earliest-first order examines an interval right after its parent, whose ends it shares.
  const std::size_t n = touch_candidates.size();
  touch_samples.resize(kTouchCached * 2 * n);
  touch_sample_time.fill(NAN);  // a sample describes this flight step only
  // Slots are written in turn, so the two ends an iteration reads and the midpoint it then computes never
  // share one.
  std::size_t cursor = 0;
  // The sample at instant s: heights at [0, n), vertical speeds at [n, 2n).
  const auto sample = [&](double s) -> const double* {
    for (std::size_t i = 0; i < kTouchCached; ++i)
      if (touch_sample_time[i] == s) return &touch_samples[i * 2 * n];
    const std::size_t slot = cursor++ % kTouchCached;
    double* out = &touch_samples[slot * 2 * n];
    const sim::Rotation st = flight_rotation->state_at(s);
    const auto c = centre(s);
    for (std::size_t i = 0; i < n; ++i) std::tie(out[i], out[n + i]) = vertex(st, c, touch_candidates[i]);
    touch_sample_time[slot] = s;
    return out;
  };
  const auto below = [&](const double* z) { return *std::min_element(z, z + n) < 0; };
  const auto clear = [&](double tl, const double* l, double tr, const double* r) {
    for (std::size_t k = 0; k < n; ++k)
      if (!vertex_clear(tl, l[k], l[n + k], tr, r[k], r[n + k])) return false;
    return true;
  };
  const double resolution = (b - a) * std::ldexp(1.0, -kTouchBisections);
  // Intervals still to examine, latest first on the stack so the earliest is examined first.
  touch_stack.clear();
  touch_stack.emplace_back(a, b);
  for (int examined = 0; !touch_stack.empty() && examined < kTouchIntervals; ++examined) {
    const auto [tl, tr] = touch_stack.back();
    touch_stack.pop_back();
    const double* l = sample(tl);
    const double* r = sample(tr);
    if (below(r)) {
      if (tr - tl <= resolution) return tl;  // bracketed: l on or above the wall, r below it
    } else if (tr - tl <= resolution || clear(tl, l, tr, r)) {
      continue;  // clear (an interval this short with both ends above the wall: a tangency within round-off)
    }
    const double tm = 0.5 * (tl + tr);
    touch_stack.emplace_back(tm, tr);
    touch_stack.emplace_back(tl, tm);
  }
  return touch_stack.empty() ? INFINITY : touch_stack.back().first;
}

}  // namespace repose
