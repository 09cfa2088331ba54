// The C API (include/repose/repose.h) against the C++ API it wraps, and the hand-over's physics: the same run
// to the bit, the caller's world frame carried through exactly, the centre of mass's velocity against its
// positions' finite differences and the kinetic energy by the parallel-axis theorem, handles used from
// several threads at once.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "repose/model/particle.hpp"
#include "repose/poses/landscape.hpp"
#include "repose/poses/rest_poses.hpp"
#include "repose/repose.h"
#include "repose/sim/settle.hpp"

namespace repose {
namespace {

struct Handles {
  repose_particle* particle = nullptr;
  repose_params* params = nullptr;
  ~Handles() {
    repose_params_free(params);
    repose_particle_free(particle);
  }
};

void make(Handles& h, const char* shape, double restitution, double friction) {
  ASSERT_EQ(repose_particle_load(shape, 2650, nullptr, &h.particle), REPOSE_OK) << repose_last_error();
  ASSERT_EQ(repose_params_new(REPOSE_UNITS_SI, &h.params), REPOSE_OK);
  ASSERT_EQ(repose_params_set_number(h.params, "restitution", restitution), REPOSE_OK) << repose_last_error();
  ASSERT_EQ(repose_params_set_number(h.params, "friction", friction), REPOSE_OK) << repose_last_error();
}

repose_state state(const Vec3& position, const Quat& q, const Vec3& velocity, const Vec3& omega) {
  return {{position.x(), position.y(), position.z()},
          {q.w(), q.x(), q.y(), q.z()},
          {velocity.x(), velocity.y(), velocity.z()},
          {omega.x(), omega.y(), omega.z()}};
}

// The same hand-over through the C++ API, as its header tells a caller to write it.
SettleResult cpp_settle(const Particle& p, SettleParams params, const repose_state& s, double floor) {
  const Quat q = Quat(s.orientation[0], s.orientation[1], s.orientation[2], s.orientation[3]).normalized();
  double lowest = INFINITY;
  for (const Vec3& v : p.hull.vertices) lowest = std::min(lowest, (q * v).z());
  params.drop_height = s.position[2] - floor + lowest;
  params.velocity = Vec3(s.velocity[0], s.velocity[1], s.velocity[2]);
  params.spin = Vec3(s.angular_velocity[0], s.angular_velocity[1], s.angular_velocity[2]);
  return settle(p, params, q);
}

struct Case {
  const char* shape;
  double restitution, friction;
  repose_state start;
  double floor;
};

std::vector<Case> cases() {
  const Quat tilt = Quat(0.9, 0.3, -0.2, 0.1).normalized();
  return {
      {"box:x=0.01,y=0.02,z=0.03", 0, INFINITY, state({1, 2, 0.1}, tilt, Vec3::Zero(), Vec3::Zero()), 0.02},
      {"irregular:seed=3", 0.5, 0.3, state({-1, 0.5, 2}, tilt, {0.4, 0, -1}, {3, -1, 2}), -0.25},
      {"tetrahedron:edge=0.02", 0, 0.6, state({0, 0, 0.05}, tilt, {0.1, 0.2, -0.3}, {0, 0, 5}), 0.0},
      {"cylinder:r=0.01,h=0.005,n=32", 0.3, INFINITY, state({5, 5, 1}, tilt, Vec3::Zero(), {10, 0, 0}), 0.75},
  };
}

TEST(CApi, SettlesExactlyAsTheCppApi) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.shape);
    Handles h;
    make(h, c.shape, c.restitution, c.friction);
    repose_result r{};
    ASSERT_EQ(repose_settle(h.particle, h.params, &c.start, c.floor, &r), REPOSE_OK) << repose_last_error();
    SettleParams params;
    params.restitution = c.restitution;
    params.friction = c.friction;
    const Particle p = load_particle(c.shape, 2650);
    const SettleResult ref = cpp_settle(p, params, c.start, c.floor);
    EXPECT_EQ(r.status, static_cast<int>(ref.status));
    EXPECT_EQ(r.rest_face, ref.rest_face);
    EXPECT_EQ(r.steps, ref.steps);
    EXPECT_EQ(r.bounces, ref.bounces);
    EXPECT_EQ(r.time, ref.time);
    EXPECT_EQ(r.orientation[0], ref.orientation.w());
    EXPECT_EQ(r.orientation[1], ref.orientation.x());
    EXPECT_EQ(r.orientation[3], ref.orientation.z());
    EXPECT_EQ(r.max_penetration, ref.max_penetration);
    // The world frame: the engine starts the centre of mass above the origin; the C API adds the caller's
    // position back. The height above the floor is the engine's to rounding (1e-12 of metres-sized numbers).
    EXPECT_NEAR(r.position[2] - c.floor, ref.com.z(), 1e-12);
    EXPECT_NEAR(r.position[0] - c.start.position[0], ref.com.x(), 1e-12);
    EXPECT_EQ(r.status, REPOSE_REST);
  }
}

// Moving the whole scene by a dyadic shift (exact in binary) moves the result by exactly that shift.
TEST(CApi, TheCallersFrameIsCarriedThroughExactly) {
  const Case c = cases()[1];
  Handles h;
  make(h, c.shape, c.restitution, c.friction);
  repose_result a{}, b{};
  ASSERT_EQ(repose_settle(h.particle, h.params, &c.start, c.floor, &a), REPOSE_OK);
  repose_state moved = c.start;
  moved.position[0] += 64;
  moved.position[1] -= 32;
  moved.position[2] += 16;
  ASSERT_EQ(repose_settle(h.particle, h.params, &moved, c.floor + 16, &b), REPOSE_OK);
  EXPECT_EQ(std::memcmp(a.orientation, b.orientation, sizeof a.orientation), 0);
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_NEAR(b.position[0] - a.position[0], 64, 1e-12);
  EXPECT_NEAR(b.position[1] - a.position[1], -32, 1e-12);
  EXPECT_NEAR(b.position[2] - a.position[2], 16, 1e-12);
}

// The state's velocity is the derivative of its position (central differences over 1e-6 s: error O(h²·a')
// and rounding 1e-16/1e-6, both far below the 1e-6 m/s asked), and its kinetic energy, ½ m v² + ½ ωᵀ I_w ω
// about the centre of mass, is the engine's (about the pivot while rotating: the parallel-axis theorem).
// Both contact phases: the paper's (infinite friction: a rotation about the contact) and the frictional one.
class CApiVelocity : public ::testing::TestWithParam<double> {};
INSTANTIATE_TEST_SUITE_P(Friction, CApiVelocity, ::testing::Values(INFINITY, 0.3));

TEST_P(CApiVelocity, TheStateVelocityIsTheDerivativeOfThePosition) {
  Handles h;
  make(h, "box:x=0.01,y=0.02,z=0.03", 0, GetParam());
  const Particle p = load_particle("box:x=0.01,y=0.02,z=0.03", 2650);
  const repose_state start =
      state({0, 0, 0.02}, Quat(0.9, 0.3, -0.2, 0.1).normalized(), Vec3::Zero(), Vec3::Zero());
  const auto at = [&](double t) {
    repose_settler* s = nullptr;
    EXPECT_EQ(repose_settler_new(h.particle, h.params, &start, 0, &s), REPOSE_OK);
    int running = 0;
    EXPECT_EQ(repose_settler_advance_to(s, t, &running), REPOSE_OK);
    repose_state out{};
    int type = -1;
    EXPECT_EQ(repose_settler_state(s, &out, nullptr), REPOSE_OK);
    EXPECT_EQ(repose_settler_contact(s, &type, nullptr), REPOSE_OK);
    repose_settler_free(s);
    return std::make_pair(out, type);
  };
  int rotating = 0;
  for (const double t : {0.03, 0.07, 0.09, 0.11}) {
    SCOPED_TRACE(t);
    const double dt = 1e-6;
    const auto [now, type] = at(t);
    const auto before = at(t - dt).first, after = at(t + dt).first;
    if (type == REPOSE_CONTACT_POINT || type == REPOSE_CONTACT_LINE) ++rotating;
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(now.velocity[k], (after.position[k] - before.position[k]) / (2 * dt), 1e-6) << k;
    const Vec3 v(now.velocity[0], now.velocity[1], now.velocity[2]);
    const Vec3 w(now.angular_velocity[0], now.angular_velocity[1], now.angular_velocity[2]);
    const Mat3 R = Quat(now.orientation[0], now.orientation[1], now.orientation[2], now.orientation[3])
                       .toRotationMatrix();
    const double energy =
        0.5 * p.mass.mass * v.squaredNorm() + 0.5 * w.dot(R * p.mass.inertia * R.transpose() * w);
    repose_settler* s = nullptr;
    ASSERT_EQ(repose_settler_new(h.particle, h.params, &start, 0, &s), REPOSE_OK);
    repose_settler_advance_to(s, t, nullptr);
    repose_result r{};
    repose_settler_result(s, &r);
    repose_settler_free(s);
    const double potential = p.mass.mass * 9.81 * (now.position[2]);
    EXPECT_NEAR(energy + potential, r.energy_end, 1e-12 * r.energy_start);
  }
  EXPECT_GE(rotating, 2);  // the times straddle the fall and the rotation
}

// While a run goes on, the points on the floor are the hull vertices within the contact band (ε·L) of the
// floor (the engine's count within one, its set being updated at its steps' ends); at rest, the support, on
// the floor.
// Issue 48: the frictional phase's ledger and fallbacks through C are the C++ result's, and close ΔE; with
// friction infinite every field is zero.
TEST(CApi, FrictionAccountIsTheCppLedger) {
  for (const Case& c : cases()) {
    Handles h;
    make(h, c.shape, c.restitution, c.friction);
    repose_settler* s = nullptr;
    ASSERT_EQ(repose_settler_new(h.particle, h.params, &c.start, c.floor, &s), REPOSE_OK)
        << repose_last_error();
    ASSERT_EQ(repose_settler_run(s), REPOSE_OK);
    repose_friction_account a{};
    repose_result r{};
    ASSERT_EQ(repose_settler_friction_account(s, &a), REPOSE_OK) << repose_last_error();
    ASSERT_EQ(repose_settler_result(s, &r), REPOSE_OK);
    repose_settler_free(s);
    if (!std::isfinite(c.friction)) {
      EXPECT_EQ(a.friction_work, 0) << c.shape;
      EXPECT_EQ(a.handovers_timed_out + a.handovers_stalled + a.zeno_captures, 0) << c.shape;
      continue;
    }
    const Particle p = load_particle(c.shape, 2650);
    const double mgl = p.mass.mass * 9.81 * p.length;
    const double residual = r.energy_end - r.energy_start + a.impact_losses + a.friction_work +
                            a.damping_work - a.normal_work + a.stopping_losses + a.drift_corrections -
                            a.repositioning + a.rest_losses + a.paper_phase_losses + a.frictionless_motion;
    EXPECT_LT(std::abs(residual), 1e-6 * mgl) << c.shape;
    EXPECT_GT(a.impact_losses, 0) << c.shape;
    EXPECT_EQ(a.handovers_stalled + a.handovers_timed_out + a.bounded_rounds, 0) << c.shape;
    EXPECT_EQ(a.pyramid_forces + a.unsolved_forces + a.unresolved_forces, 0) << c.shape;
  }
  repose_friction_account a{};
  EXPECT_EQ(repose_settler_friction_account(nullptr, &a), REPOSE_ERROR_NULL_POINTER);
}

TEST(CApi, ContactPointsAreTheVerticesInTheBand) {
  Handles h;
  make(h, "irregular:seed=3", 0, INFINITY);
  const Particle p = load_particle("irregular:seed=3", 2650);
  const double floor = 0.5, band = 0.05 * p.length;
  const repose_state start = state({2, 1, floor + 0.8 * p.length}, Quat(0.9, 0.3, -0.2, 0.1).normalized(),
                                   Vec3::Zero(), Vec3::Zero());
  repose_settler* s = nullptr;
  ASSERT_EQ(repose_settler_new(h.particle, h.params, &start, floor, &s), REPOSE_OK);
  int running = 1, checked = 0;
  const double every = 0.002 * std::sqrt(p.length / 9.81);  // samples between the engine's long steps
  for (int k = 1; running && k < 100000; ++k) {
    ASSERT_EQ(repose_settler_advance_to(s, k * every, &running), REPOSE_OK);
    int type = -1, count = 0;
    repose_settler_contact(s, &type, &count);
    std::size_t n = 0;
    std::vector<double> points(3 * 64);
    const int code = repose_settler_contact_points(s, points.data(), 64, &n);
    ASSERT_EQ(code, REPOSE_OK) << repose_last_error();
    if (!running) {  // at rest: the support, on the floor (1e-12 of metre-sized coordinates)
      ASSERT_GE(n, 3u);
      for (std::size_t i = 0; i < n; ++i) EXPECT_NEAR(points[3 * i + 2], floor, 1e-12);
      break;
    }
    if (type == REPOSE_CONTACT_FREE_FALL) continue;
    // The hull vertices within the band at the state's pose, counted here from the state (the engine's own
    // contact set may lag inside a step, so it is not the reference).
    repose_state now{};
    repose_settler_state(s, &now, nullptr);
    const Quat q(now.orientation[0], now.orientation[1], now.orientation[2], now.orientation[3]);
    std::size_t expected = 0;
    for (const Vec3& v : p.hull.vertices) expected += now.position[2] + (q * v).z() - floor <= band ? 1 : 0;
    EXPECT_EQ(n, expected);
    EXPECT_LE(std::abs(static_cast<int>(n) - count), 1);
    for (std::size_t i = 0; i < n; ++i) {
      EXPECT_GE(points[3 * i + 2] - floor, -1e-9 * p.length);
      EXPECT_LE(points[3 * i + 2] - floor, band + 1e-12);
    }
    ++checked;
  }
  EXPECT_GT(checked, 10);
  repose_settler_free(s);
}

TEST(CApi, PosesAreTheCatalogue) {
  Handles h;
  make(h, "irregular:seed=11", 0, INFINITY);
  const Particle p = load_particle("irregular:seed=11", 2650);
  const RestLandscape landscape = compute_rest_landscape(p);
  const RestPoseCatalog ref = catalog_rest_poses(p, landscape, default_persistence(p, is_smooth_surface(p)));
  repose_poses* poses = nullptr;
  ASSERT_EQ(repose_poses_new(h.particle, -1, &poses), REPOSE_OK);
  int count = 0;
  repose_poses_count(poses, &count);
  ASSERT_EQ(count, static_cast<int>(ref.poses.size()));
  for (int i = 0; i < count; ++i) {
    repose_pose pose{};
    ASSERT_EQ(repose_poses_get(poses, i, &pose), REPOSE_OK);
    EXPECT_EQ(pose.face, ref.poses[static_cast<std::size_t>(i)].face);
    EXPECT_EQ(pose.probability, ref.poses[static_cast<std::size_t>(i)].quasi_static_probability);
    EXPECT_EQ(pose.com_height, ref.poses[static_cast<std::size_t>(i)].com_height);
  }
  repose_particle_free(h.particle);  // the catalogue keeps its particle alive
  h.particle = nullptr;
  int face_pose = -1;
  EXPECT_EQ(repose_poses_of_face(poses, ref.poses[0].face, &face_pose), REPOSE_OK);
  EXPECT_EQ(face_pose, 0);
  repose_poses_free(poses);
}

// One particle shared by four threads, each with its own params and settler: the same results as one by
// one, and each thread's last error its own.
TEST(CApi, HandlesWorkFromSeveralThreads) {
  repose_particle* particle = nullptr;
  ASSERT_EQ(repose_particle_load("irregular:seed=5", 1, nullptr, &particle), REPOSE_OK);
  const auto run = [&](int i, repose_result& out, std::string& error) {
    repose_params* params = nullptr;
    repose_params_new(REPOSE_UNITS_SI, &params);
    repose_params_set_number(params, "restitution", 0.1 * i);
    const repose_state start =
        state({0, 0, 1.0 + i}, Quat(1, 0.1 * i, 0.2, -0.3).normalized(), Vec3::Zero(), Vec3(1, 0, 0));
    repose_settle(particle, params, &start, 0, &out);
    const char* const names[] = {"x0", "x1", "x2", "x3"};
    repose_params_set_number(params, names[i], 1);  // fails: no such parameter
    error = repose_last_error();
    repose_params_free(params);
  };
  std::vector<repose_result> alone(4), together(4);
  std::vector<std::string> errors(4), errors_together(4);
  for (int i = 0; i < 4; ++i) run(i, alone[static_cast<std::size_t>(i)], errors[static_cast<std::size_t>(i)]);
  std::vector<std::thread> threads;
  for (int i = 0; i < 4; ++i)
    threads.emplace_back(run, i, std::ref(together[static_cast<std::size_t>(i)]),
                         std::ref(errors_together[static_cast<std::size_t>(i)]));
  for (std::thread& t : threads) t.join();
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(std::memcmp(alone[i].orientation, together[i].orientation, sizeof alone[i].orientation), 0);
    EXPECT_EQ(alone[i].steps, together[i].steps);
    EXPECT_EQ(errors_together[i], errors[i]);
    EXPECT_NE(errors[i].find("unknown parameter 'x" + std::to_string(i) + "'"), std::string::npos)
        << errors[i];
  }
  repose_particle_free(particle);
}

}  // namespace
}  // namespace repose
