// Random settling cases and the properties every run must satisfy, shared by the property tests.
//
// A case is fully determined by (master seed, index): its own splitmix64 stream picks a shape class, a shape
// spec (dimensions rounded to 4 significant digits, so the spec string is exact), a smooth mode, a uniform
// random orientation (Shoemake), a drop height and a damping coefficient. repro() prints the equivalent
// `repose settle` command line; the orientation goes through format_orientation/parse_orientation so the
// command line reproduces the run bit for bit. Units are CGS (cm, g, s; g = 981 cm/s²) as in the paper.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <numbers>
#include <repose/model/orientation.hpp>
#include <repose/model/params.hpp>
#include <repose/model/particle.hpp>
#include <repose/sim/settle.hpp>
#include <string>
#include <vector>

#include "../support/equilibrium_oracle.hpp"
#include "gravity.hpp"

namespace repose::property {

constexpr double kDensity = 1.2;

/// splitmix64 → doubles in [0, 1): the only source of randomness (no std distributions, whose output is
/// implementation-defined).
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  double log_uniform(double lo, double hi) { return lo * std::exp(std::log(hi / lo) * uniform()); }
  int pick(int n) { return static_cast<int>(uniform() * n); }

 private:
  std::uint64_t state_;
};

/// Uniform random rotation (Shoemake 1992).
inline Quat shoemake(Rng& rng) {
  const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
  const double two_pi = 2 * std::numbers::pi;
  return Quat(std::sqrt(u1) * std::cos(two_pi * u3), std::sqrt(1 - u1) * std::sin(two_pi * u2),
              std::sqrt(1 - u1) * std::cos(two_pi * u2), std::sqrt(u1) * std::sin(two_pi * u3));
}

enum class ShapeClass { irregular, box, tetrahedron, cylinder, ellipsoid, count };

inline const char* name(ShapeClass c) {
  switch (c) {
    case ShapeClass::irregular:
      return "irregular";
    case ShapeClass::box:
      return "box";
    case ShapeClass::tetrahedron:
      return "tetrahedron";
    case ShapeClass::cylinder:
      return "cylinder";
    case ShapeClass::ellipsoid:
      return "ellipsoid";
    default:
      return "?";
  }
}

inline const char* name(SmoothMode m) {
  return m == SmoothMode::on ? "on" : m == SmoothMode::off ? "off" : "auto";
}

struct Case {
  int index = 0;
  ShapeClass shape = ShapeClass::box;
  std::string spec;
  SmoothMode smooth = SmoothMode::automatic;
  Quat orientation = Quat::Identity();
  double drop_fraction = 0;     ///< drop height as a fraction of L (the particle is needed for L)
  double damping_fraction = 0;  ///< damping as a fraction of m·L²·sqrt(g/L)
  long max_steps = 0;           ///< 0: the default SettleParams::max_steps
  double damping = -1;          ///< if ≥ 0, the damping coefficient itself (overrides damping_fraction)
  double drop_height = -1;      ///< if ≥ 0, the drop height itself (overrides drop_fraction)
  Integrator integrator = Integrator::paper;
  double tolerance = SettleParams{}.tolerance;  ///< the adaptive integrator's
  // A toss (make_case's `tossed`): E, μ (finite: the frictional contact phase), and the centre of mass's
  // velocity and the angular velocity in units of sqrt(g·L) and sqrt(g/L).
  bool tossed = false;
  double restitution = 0, friction = INFINITY;
  Vec3 velocity_fraction = Vec3::Zero(), spin_fraction = Vec3::Zero();
};

/// Step budget of a possibly-smooth ellipsoid in the budgeted sweep (~6 s of CPU at its worst).
constexpr long kSmoothStepBudget = 200'000;

/// A number rounded to 4 significant digits, as written in the spec.
inline std::string num4(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

inline std::string num17(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

inline std::uint64_t case_seed(std::uint64_t master, int index) {
  Rng mix(master ^ (0x5851f42d4c957f2dULL * static_cast<std::uint64_t>(index + 1)));
  return mix.next();
}

/// The case with this index. Class mix: 35 % irregular, 20 % box, 10 % tetrahedron, 29 % cylinder, 6 %
/// ellipsoid (`full`: 20 % cylinder, 15 % ellipsoid); drop height 0 for 70 % of cases, else uniform in
/// (0, 2L); damping 0 for 80 %, else log-uniform in [1e-3, 1]·m·L²·sqrt(g/L). Ellipsoids are icospheres of
/// frequency 3 or 4 (`full`: 4, 6 or 10), smooth mode auto 12.5 % / on 12.5 % / off 75 % (`full`: 50/25/25).
/// A smooth undamped ellipsoid rocks until the small impacts between its facets have taken its kinetic
/// energy below 1e-9·m·g·L: 30 000 to 600 000 steps, 0.2 s to 20 s of CPU. The budgeted sweep therefore
/// gives every possibly-smooth ellipsoid a damping (log-uniform in [1e-2, 1], as the paper does for its
/// smooth ellipsoid), keeps them few and coarse, and stops them after kSmoothStepBudget steps (a smooth
/// particle need not rest; one that hits the budget is counted in the summary); `full` is for the big local
/// sweep, with the default limits. `coarse` (the sanitizer build's sweep, where every step costs ~100×) keeps
/// the same draws but the cheapest meshes: irregular grains of frequency 3, cylinders of 6 or 16 sides.
inline Case make_case(std::uint64_t master, int index, bool full = false, bool coarse = false,
                      bool tossed = false) {
  Rng rng(case_seed(master, index));
  Case c;
  c.index = index;
  const double u = rng.uniform();
  const double cylinders = full ? 0.85 : 0.94;
  c.shape = u < 0.35        ? ShapeClass::irregular
            : u < 0.55      ? ShapeClass::box
            : u < 0.65      ? ShapeClass::tetrahedron
            : u < cylinders ? ShapeClass::cylinder
                            : ShapeClass::ellipsoid;
  switch (c.shape) {
    case ShapeClass::irregular: {
      const int seed = 1 + rng.pick(12);
      const int n = coarse ? (rng.pick(4), 3) : 3 + rng.pick(4);  // icosphere frequency 3..6
      c.spec = "irregular:seed=" + std::to_string(seed) + ",n=" + std::to_string(n);
      break;
    }
    case ShapeClass::box: {
      const double x = rng.log_uniform(0.2, 2.0);
      c.spec = "box:x=" + num4(x) + ",y=" + num4(x * rng.log_uniform(0.2, 5)) +
               ",z=" + num4(x * rng.log_uniform(0.2, 5));
      break;
    }
    case ShapeClass::tetrahedron:
      c.spec = "tetrahedron:edge=" + num4(rng.log_uniform(0.2, 3.0));
      break;
    case ShapeClass::cylinder: {
      static constexpr int kSides[] = {6, 16, 64}, kCoarseSides[] = {6, 16, 6};
      const double r = rng.log_uniform(0.1, 1.5);
      c.spec = "cylinder:r=" + num4(r) + ",h=" + num4(r * rng.log_uniform(0.1, 6)) +
               ",n=" + std::to_string((coarse ? kCoarseSides : kSides)[rng.pick(3)]);
      break;
    }
    case ShapeClass::ellipsoid: {
      static constexpr int kFull[] = {4, 6, 10};
      static constexpr int kLight[] = {3, 4, 3};
      const double a = rng.log_uniform(0.2, 1.5);
      c.spec = "ellipsoid:a=" + num4(a) + ",b=" + num4(a * rng.log_uniform(0.3, 3)) +
               ",c=" + num4(a * rng.log_uniform(0.3, 3)) +
               ",n=" + std::to_string((full ? kFull : kLight)[rng.pick(3)]);
      const double s = rng.uniform();
      const double a_share = full ? 0.5 : 0.125, on_share = full ? 0.75 : 0.25;
      c.smooth = s < a_share ? SmoothMode::automatic : s < on_share ? SmoothMode::on : SmoothMode::off;
      break;
    }
    default:
      break;
  }
  c.orientation = parse_orientation(format_orientation(shoemake(rng)));
  c.drop_fraction = rng.uniform() < 0.7 ? 0.0 : 2 * rng.uniform();
  c.damping_fraction = rng.uniform() < 0.8 ? 0.0 : rng.log_uniform(1e-3, 1.0);
  if (!full && c.shape == ShapeClass::ellipsoid && c.smooth != SmoothMode::off && c.damping_fraction == 0)
    c.damping_fraction = rng.log_uniform(1e-2, 1.0);
  if (!full && c.shape == ShapeClass::ellipsoid && c.smooth != SmoothMode::off)
    c.max_steps = kSmoothStepBudget;
  if (tossed) {
    // Tossed with finite friction (issue 34): E uniform in [0, 0.9], μ 0 for 5 %, else log-uniform in
    // [0.05, 3]; up to sqrt(g·L) of velocity and 5·sqrt(g/L) of spin in random directions.
    c.tossed = true;
    c.restitution = 0.9 * rng.uniform();
    c.friction = rng.uniform() < 0.05 ? 0.0 : rng.log_uniform(0.05, 3.0);
    const auto direction = [&] {
      const Vec3 v(2 * rng.uniform() - 1, 2 * rng.uniform() - 1, 2 * rng.uniform() - 1);
      return Vec3(v / std::max(v.norm(), 1e-12));
    };
    c.velocity_fraction = rng.uniform() * direction();
    c.spin_fraction = 5 * rng.uniform() * direction();
  }
  return c;
}

inline SettleParams params_for(const Case& c, const Particle& p) {
  SettleParams prm;
  prm.gravity = test::kGravityCGS;
  prm.smooth = c.smooth;
  prm.integrator = c.integrator;
  prm.tolerance = c.tolerance;
  prm.drop_height = c.drop_height >= 0 ? c.drop_height : c.drop_fraction * p.length;
  prm.damping = c.damping >= 0 ? c.damping
                               : c.damping_fraction * p.mass.mass * p.length * p.length *
                                     std::sqrt(test::kGravityCGS / p.length);
  if (c.max_steps > 0) prm.max_steps = c.max_steps;
  if (c.tossed) {
    prm.restitution = c.restitution;
    prm.friction = c.friction;
    prm.velocity = c.velocity_fraction * std::sqrt(test::kGravityCGS * p.length);
    prm.spin = c.spin_fraction * std::sqrt(test::kGravityCGS / p.length);
  }
  return prm;
}

/// The `repose settle` command line that reproduces the case.
inline std::string repro(const Case& c, const Particle& p) {
  const SettleParams prm = params_for(c, p);
  std::string s = "repose settle '" + c.spec + "' --orientation " + format_orientation(c.orientation) +
                  " --units cgs --density 1.2";
  if (prm.drop_height > 0) s += " --drop-height " + num17(prm.drop_height);
  if (prm.damping > 0) s += " --damping " + num17(prm.damping);
  if (c.smooth != SmoothMode::automatic) s += std::string(" --smooth ") + name(c.smooth);
  if (c.max_steps > 0) s += " --max-steps " + std::to_string(c.max_steps);
  if (c.integrator == Integrator::adaptive) s += " --integrator adaptive";
  if (c.tolerance != SettleParams{}.tolerance) s += " --tolerance " + num17(c.tolerance);
  if (c.tossed) {
    const auto vec = [](const Vec3& v) { return num17(v.x()) + "," + num17(v.y()) + "," + num17(v.z()); };
    s += " --restitution " + num17(prm.restitution) + " --friction " + num17(prm.friction) + " --velocity " +
         vec(prm.velocity) + " --spin " + vec(prm.spin);
  }
  return s + "   # case " + std::to_string(c.index);
}

/// What one run did, and every property it broke.
struct Outcome {
  SettleResult result;
  std::vector<std::string> violations;
  double seconds = 0;
  double max_energy_rise = 0;   ///< largest rise of kinetic + potential energy between samples / (m·g·L)
  double energy_overshoot = 0;  ///< largest (E − E_start) over the run / (m·g·L)
  double min_vertex_z = 0;      ///< lowest hull vertex over every sample / L (independent of the engine)
  double rest_snap = 0;  ///< rotation (rad) between the last moving sample and the rest pose (the flush snap)
  long samples = 0;
};

/// Tolerances on energy, as fractions of m·g·L: a rise between consecutive samples, and the whole run's
/// kinetic + potential energy above its start. Impacts (momentum about the new support conserved: the
/// kinetic-metric projection of the velocity onto the new constraint) and damping only remove energy; what
/// can add some is the trapezoidal rule's error at the default step (1e-3·sqrt(L/g)), the pseudo-time
/// iteration's tolerance (1e-8 on the quaternion) and putting a support or the rest face exactly on the wall
/// (≤ 1e-9·L of height). Measured over the 10,000-drop sweep: largest rise 1.7e-11, largest overshoot
/// 1.1e-10 (m·g·L). The tolerances are 6× and 9× those; a damping moment of the wrong sign, an impact that
/// keeps the normal velocity or a lift of the body by 1e-9·L would exceed them.
/// The adaptive integrator's local error bound `tolerance` is on the state scaled by L and sqrt(L/g), in
/// which kinetic energy is in units of m·g·L, so its energy error per step, and that of its dense output
/// between steps, is of that order: measured at the default 1e-9 over the sweep, largest rise between samples
/// 5.2e-9, largest overshoot over a run 4.0e-9 (m·g·L). Its allowances are 10× the tolerance (never below the
/// paper scheme's); a damping moment of the wrong sign or an impact that keeps the normal velocity gives
/// rises of 1e-3 and more.
constexpr double kEnergyRise = 1e-10;
constexpr double kEnergyOvershoot = 1e-9;
inline double energy_rise_allowance(const SettleParams& prm) {
  return prm.integrator == Integrator::adaptive ? std::max(kEnergyRise, 10 * prm.tolerance) : kEnergyRise;
}
inline double energy_overshoot_allowance(const SettleParams& prm) {
  return prm.integrator == Integrator::adaptive ? std::max(kEnergyOvershoot, 10 * prm.tolerance)
                                                : kEnergyOvershoot;
}

/// Consecutive steps with no progress of time after which a run is declared stalled.
constexpr long kStallSteps = 1000;

/// The value of `key` in a shape spec such as "box:x=1,y=2,z=3" (NaN if absent).
inline double spec_value(const std::string& spec, const std::string& key) {
  std::size_t at = spec.find(':');
  while (at != std::string::npos) {
    const std::size_t end = spec.find(',', at + 1);
    const std::string item = spec.substr(at + 1, end == std::string::npos ? std::string::npos : end - at - 1);
    if (item.rfind(key + "=", 0) == 0) return std::stod(item.substr(key.size() + 1));
    at = end;
  }
  return NAN;
}

/// The exact rest poses of the shapes that have them in closed form, from the spec's dimensions: a box rests
/// on a face (down normal ±x, ±y or ±z, centre of mass at half that extent), a regular tetrahedron at its
/// inradius a·sqrt(6)/12, an n-gon cylinder on a base (h/2) or on a side (the apothem r·cos(π/n)). Empty
/// if the rest matches one of them to 1e-9 (normal) and 1e-9·L (height), else what is wrong.
inline std::string closed_form_rest_problem(const std::string& spec, const SettleResult& r, double L) {
  const Vec3 d = r.down_normal_body;
  const double h = r.com.z();
  auto near = [&](double a, double b) { return std::abs(a - b) <= 1e-9 * L; };
  std::string kind = spec.substr(0, spec.find(':'));
  if (kind == "box") {
    int k = 0;
    d.cwiseAbs().maxCoeff(&k);
    const double half = spec_value(spec, std::string(1, "xyz"[k])) / 2;
    if (std::abs(std::abs(d[k]) - 1) > 1e-9 || !near(h, half))
      return "box rest (down " + num17(d.x()) + "," + num17(d.y()) + "," + num17(d.z()) + ", height " +
             num17(h) + ") is not a face at half its extent " + num17(half);
  } else if (kind == "tetrahedron") {
    const double inradius = spec_value(spec, "edge") * std::sqrt(6.0) / 12;
    if (!near(h, inradius))
      return "tetrahedron rests at " + num17(h) + ", not its inradius " + num17(inradius);
  } else if (kind == "cylinder") {
    const double radius = spec_value(spec, "r"), height = spec_value(spec, "h"), n = spec_value(spec, "n");
    const bool base = std::abs(std::abs(d.z()) - 1) <= 1e-9 && near(h, height / 2);
    const bool side = std::abs(d.z()) <= 1e-9 && near(h, radius * std::cos(std::numbers::pi / n));
    if (!base && !side)
      return "cylinder rest (down z " + num17(d.z()) + ", height " + num17(h) + ") is neither base nor side";
  }
  return "";
}

/// Runs the case and checks every property (see the test's header comment).
/// A hull face's smallest width: over its edges, the largest distance of its points from the edge's line.
inline double face_width(const Particle& p, int face) {
  const auto& loop = p.hull.faces[static_cast<std::size_t>(face)].loop;
  double width = INFINITY;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec3 a = p.hull.vertices[static_cast<std::size_t>(loop[i])];
    const Vec3 e = (p.hull.vertices[static_cast<std::size_t>(loop[(i + 1) % loop.size()])] - a).normalized();
    double farthest = 0;
    for (int k : loop) {
      const Vec3 d = p.hull.vertices[static_cast<std::size_t>(k)] - a;
      farthest = std::max(farthest, (d - d.dot(e) * e).norm());
    }
    width = std::min(width, farthest);
  }
  return width;
}

inline Outcome run_case(const Case& c, const Particle& p) {
  Outcome o;
  const double L = p.length;
  const double mgl = p.mass.mass * test::kGravityCGS * L;
  const SettleParams prm = params_for(c, p);
  auto fail = [&](const std::string& what) { o.violations.push_back(what); };

  bool finite = true, first = true, stalled = false;
  double e_prev = 0, e_start = 0, lowest = INFINITY;
  Quat q_prev = c.orientation;
  double omega_prev = 0, t_prev = 0;
  auto observe = [&](const Sample& s) {
    ++o.samples;
    const bool ok = std::isfinite(s.t) && s.orientation.coeffs().allFinite() && s.omega.allFinite() &&
                    s.com.allFinite() && std::isfinite(s.kinetic_energy) && std::isfinite(s.potential_energy);
    if (!ok) {
      if (finite) fail("non-finite sample at t=" + num17(s.t));
      finite = false;
      return;
    }
    const double e = s.kinetic_energy + s.potential_energy;
    if (first) {
      e_start = e_prev = e;
      first = false;
    }
    o.max_energy_rise = std::max(o.max_energy_rise, (e - e_prev) / mgl);
    o.energy_overshoot = std::max(o.energy_overshoot, (e - e_start) / mgl);
    e_prev = e;
    if (s.omega.squaredNorm() > 0) {  // moving: the rest pose is snapped from the last such sample
      q_prev = s.orientation;
      omega_prev = s.omega.norm();
      t_prev = s.t;
    }
    // Independent penetration check: the lowest hull vertex at this sample.
    const Vec3 r3 = s.orientation.normalized().toRotationMatrix().row(2).transpose();
    for (const Vec3& v : p.hull.vertices) lowest = std::min(lowest, s.com.z() + r3.dot(v));
  };
  const auto t0 = std::chrono::steady_clock::now();
  try {
    // Settler::run's loop, plus a watchdog: time must advance. kStallSteps steps in a row without any
    // progress of t is a livelock (the run would otherwise burn max_steps = 2e7 steps, minutes of CPU).
    Settler settler(p, prm, c.orientation);
    observe(settler.sample());
    double last_t = -1;
    long frozen = 0;
    while (settler.step()) {
      const Sample s = settler.sample();
      observe(s);
      frozen = s.t == last_t ? frozen + 1 : 0;
      last_t = s.t;
      if (frozen >= kStallSteps) {
        fail("stalled: " + std::to_string(kStallSteps) + " steps without time advancing at t=" + num17(s.t));
        stalled = true;
        break;
      }
    }
    if (settler.status() != Status::running) observe(settler.sample());
    o.result = settler.result();
    if (o.result.status == Status::rest) o.rest_snap = o.result.orientation.angularDistance(q_prev);
  } catch (const std::exception& e) {
    fail(std::string("threw: ") + e.what());
    o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return o;
  }
  o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  o.min_vertex_z = lowest / L;
  const SettleResult& r = o.result;

  if (r.status == Status::running && !stalled) fail("ended with status running");
  if (r.max_penetration > 1e-9 * L) fail("max_penetration " + num17(r.max_penetration / L) + " L > 1e-9 L");
  if (lowest < -1e-9 * L) fail("a sample has a hull vertex at z = " + num17(lowest / L) + " L < -1e-9 L");
  if (o.max_energy_rise > energy_rise_allowance(prm))
    fail("energy rose by " + num17(o.max_energy_rise) + " m·g·L between consecutive samples");

  if (prm.drop_height > 0 && !c.tossed) {
    const double touch = std::sqrt(2 * prm.drop_height / test::kGravityCGS);
    if (r.phases.empty() || r.phases.front().contact != ContactType::free_fall ||
        std::abs(r.phases.front().t1 - touch) > 1e-9 * touch)
      fail("free fall did not end at sqrt(2h/g) = " + num17(touch));
  }

  if (o.energy_overshoot > energy_overshoot_allowance(prm))
    fail("energy rose " + num17(o.energy_overshoot) + " m·g·L above its start over the run");

  if (r.status == Status::rest) {
    if (r.rest_face < 0 || r.rest_face >= static_cast<int>(p.hull.faces.size())) {
      fail("rest without a valid rest_face (" + std::to_string(r.rest_face) + ")");
    } else {
      const HullFace& face = p.hull.faces[r.rest_face];
      const Vec3 down = r.orientation * face.normal;
      if ((down - Vec3(0, 0, -1)).norm() > 1e-9)
        fail("rest face normal off (0,0,-1) by " + num17((down - Vec3(0, 0, -1)).norm()));
      // The face plane n·x = offset through the body origin (the centre of mass): flush means com.z = offset.
      if (std::abs(r.com.z() - face.offset) > 1e-9 * L)
        fail("rest centre of mass at z=" + num17(r.com.z()) + ", face offset " + num17(face.offset));
    }
    // Static equilibrium judged by the test alone, from the mesh vertices (equilibrium_oracle.hpp).
    const oracle::RestCheck eq = oracle::check_rest(p.mesh.vertices, r.orientation, r.com, L);
    if (!eq.problem.empty()) fail("rest is not a static equilibrium: " + eq.problem);
    if (const std::string why = closed_form_rest_problem(c.spec, r, L); !why.empty()) fail(why);
    if (r.contact_points.size() < 3)
      fail("rest on " + std::to_string(r.contact_points.size()) + " supporting points (< 3)");
    for (const Vec3& cp : r.contact_points)
      if (std::abs(cp.z()) > 1e-12 * L) {
        fail("supporting point at z = " + num17(cp.z() / L) + " L, not within 1e-12 L of the wall");
        break;
      }
    // The rest pose is where the motion took the particle: from the last moving sample, one step of Δt turns
    // the body by at most |ω|·Δt + ½·α·Δt², with α ≤ m·g·L / I_min (the weight's moment about any support is
    // at most m·g·L, and the inertia about any point is at least the smallest principal moment about the
    // centre of mass), then the flush alignment of a face whose points all touch within 1e-9·L; smooth
    // particles too (they rest only by landing on three points of their bottom facet). The factor 1.5 leaves
    // room for the gyroscopic term, which the bound leaves out.
    const double step = r.time - t_prev;
    const double alpha = p.mass.mass * test::kGravityCGS * L / p.mass.principal_moments.minCoeff();
    // The frictional phase (finite μ) lays the face flush once all its points are within its band of the
    // wall, 1e-7·L (kFrictionalBand, docs/method.md): a turn of at most band / w, w the face's smallest
    // width.
    double flush = 0;
    if (std::isfinite(prm.friction) && r.rest_face >= 0 &&
        r.rest_face < static_cast<int>(p.hull.faces.size()))
      flush = 1e-7 * L / face_width(p, r.rest_face);
    const double reach = 1.5 * (omega_prev * step + 0.5 * alpha * step * step + flush) + 1e-6;
    if (o.rest_snap > reach)
      fail("rest pose is a " + num17(o.rest_snap) +
           " rad rotation from the last moving state (one step turns ≤ " + num17(reach) +
           " rad): rest declared before the face landed");
    // Every hull vertex at or above the wall in the final pose.
    double final_low = INFINITY;
    for (const Vec3& v : p.hull.vertices) final_low = std::min(final_low, (r.com + r.orientation * v).z());
    if (final_low < -1e-9 * L) fail("rest pose penetrates: lowest vertex " + num17(final_low / L) + " L");
  } else if (!stalled) {
    fail(std::string(r.smooth ? "smooth" : "non-smooth") + " particle did not rest: status " +
         to_string(r.status));
  }
  return o;
}

}  // namespace repose::property
