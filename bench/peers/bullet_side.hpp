// Bullet's side of the peer benchmark (peer_bullet.cpp): the units and the rest test both engines share, the
// toss and Bullet's options, and the Bullet world that drops one body (its comment in peer_bullet.cpp).
#pragma once

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <repose/geometry/types.hpp>
#include <repose/model/particle.hpp>
#include <repose/poses/sampling.hpp>
#include <vector>

namespace peer {

using Clock = std::chrono::steady_clock;
using repose::Quat;
using repose::Vec3;

inline constexpr double kDensity = 1000.0;  // kg/m³
inline constexpr double kGravity = 9.81;    // m/s²
inline constexpr double kWindowTime = 0.1;  // the rest test's window (s)
inline constexpr double kRestFraction = 1e-3;
inline constexpr double kMaxTime = 20.0;  // s

// A toss for every drop (--toss E,MU), or none.
struct TossOptions {
  bool active = false;
  double restitution = 0, friction = INFINITY;
  // repose's restitution threshold (--match-threshold: Bullet's own restitution velocity threshold, below
  // which Bullet's impacts are plastic; 0: repose's default, E at every speed).
  double threshold = 0;
  static constexpr double kHeight = 4, kVelocity = 1.5, kSpin = 1.5;  // × L, sqrt(g·L), sqrt(g/L)
};

// Departures from Bullet's defaults, for comparison runs (both off by default).
struct BulletOptions {
  double step = 1e-3;  // Bullet's fixed step (s): --bullet-step, or chosen per shape (bullet_steps.hpp)
  bool sleep = true;   // Bullet's deactivation (default on); --bullet-no-sleep turns it off
  double damping = 0;  // repose's damping coefficient C to mirror as Bullet angular damping (0: none)
  // Bullet's length unit, in its units per metre (--bullet-units): 1, metres; 100, centimetres, the unit a
  // Bullet user picks for bodies of a centimetre, so that the body is about one unit and Bullet's default
  // margin (0.04 units), sleeping thresholds and restitution threshold fit it. Masses stay in kg, times in s.
  double units = 1;
  TossOptions toss;  // restitution and friction of the body (the ground's 1 and 1), with --toss
};

// Bullet's side: one world per shape; each drop removes the body, resets it and adds it again.
class BulletSide {
 public:
  BulletSide(const repose::Particle& particle, const BulletOptions& options)
      : dispatcher_(&config_),
        world_(&dispatcher_, &broadphase_, &solver_, &config_),
        ground_shape_({0, 0, 1}, 0) {
    units_ = options.units;
    world_.setGravity({0, 0, -kGravity * units_});
    ground_ =
        std::make_unique<btRigidBody>(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, &ground_shape_));
    world_.addRigidBody(ground_.get());
    // Bullet's body frame: the centre of mass at the origin and the principal axes (Bullet's inertia is
    // diagonal), i.e. repose's body frame rotated by the principal axes A: x_bullet = Aᵀ x_body.
    axes_ = particle.mass.principal_axes;
    for (const Vec3& v : particle.hull.vertices) {
      const Vec3 p = units_ * (axes_.transpose() * v);
      vertices_.push_back(p);
      hull_.addPoint({p.x(), p.y(), p.z()}, false);
    }
    hull_.recalcLocalAabb();
    const Vec3 moments = units_ * units_ * particle.mass.principal_moments;
    btRigidBody::btRigidBodyConstructionInfo info(particle.mass.mass, nullptr, &hull_,
                                                  {moments.x(), moments.y(), moments.z()});
    body_ = std::make_unique<btRigidBody>(info);
    // --bullet-damping: repose's damping torque −C·ω as Bullet angular damping, at the decay rate C/I of the
    // mean principal moment I (Bullet scales ω by (1 − d)^dt each step, so d = 1 − exp(−C/I · 1 s)).
    if (options.damping > 0) body_->setDamping(0, 1 - std::exp(-options.damping / (moments.sum() / 3)));
    if (options.toss.active) {
      ground_->setRestitution(1);
      ground_->setFriction(1);
      body_->setRestitution(options.toss.restitution);
      body_->setFriction(std::isfinite(options.toss.friction) ? options.toss.friction : BT_LARGE_FLOAT);
    }
    sleep_ = options.sleep;
    dt_ = options.step;
    // The window's two halves hold the same whole number of steps (at 1 ms: 100 steps, 0.1 s).
    window_ = 2 * std::max(1L, std::lround(kWindowTime / 2 / dt_));
    world_.addRigidBody(body_.get());
  }

  double margin() const { return hull_.getMargin(); }

  struct Drop {
    bool rested = false;
    bool slept = false;            // ended by Bullet's deactivation rather than by the rest window
    double time = 0;               // simulated time (s)
    double seconds = 0;            // wall-clock time of the drop (s)
    double max_depth = -INFINITY;  // greatest depth of a hull vertex below z = 0 over the run (m; < 0: above)
    Vec3 down_body;                // final direction at the wall, repose's body frame
  };

  // Drop from rest on the wall, or tossed (`toss`, world frame) with the lowest point `height` above it; the
  // arguments and the Drop in metres, whatever Bullet's units.
  Drop drop(const Quat& q, double length, const repose::Toss& toss = {}, double height = 0) {
    Drop out;
    length *= units_;
    height *= units_;
    const auto t0 = Clock::now();
    // Orientation of Bullet's (principal) frame: world = R_q·x_body = R_q·A·x_bullet.
    const repose::Mat3 r = q.toRotationMatrix() * axes_;
    btMatrix3x3 basis(r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1), r(2, 2));
    // Lowest point of Bullet's collision shape (the hull grown by its margin) touching the plane.
    double lowest = INFINITY;
    for (const Vec3& p : vertices_) lowest = std::min(lowest, r.row(2).dot(p));
    const btTransform start(basis, {0, 0, height + margin() - lowest});
    const Vec3 velocity = units_ * toss.velocity;
    const btVector3 v(velocity.x(), velocity.y(), velocity.z());
    const btVector3 w(toss.spin.x(), toss.spin.y(), toss.spin.z());
    world_.removeRigidBody(body_.get());
    body_->setWorldTransform(start);
    body_->setInterpolationWorldTransform(start);
    body_->setLinearVelocity(v);
    body_->setAngularVelocity(w);
    body_->setInterpolationLinearVelocity(v);
    body_->setInterpolationAngularVelocity(w);
    body_->clearForces();
    body_->forceActivationState(sleep_ ? ACTIVE_TAG : DISABLE_DEACTIVATION);
    body_->setDeactivationTime(0);
    world_.addRigidBody(body_.get());
    Clock::duration timed = Clock::now() - t0;

    const double v_tol = kRestFraction * std::sqrt(kGravity * units_ * length);
    const double w_tol = kRestFraction * std::sqrt(kGravity * units_ / length);
    std::vector<double> speed(window_), spin(window_);  // ring buffers of the last 0.1 s
    const long max_steps = std::lround(kMaxTime / dt_);
    long step = 0;
    for (; step < max_steps;) {
      const auto s0 = Clock::now();
      world_.stepSimulation(dt_, 0);
      speed[step % window_] = body_->getLinearVelocity().length();
      spin[step % window_] = body_->getAngularVelocity().length();
      ++step;
      const bool slept = body_->getActivationState() == ISLAND_SLEEPING;
      bool done = slept;
      if (!done && step >= window_) {
        double v[2] = {0, 0}, w[2] = {0, 0};  // sums over the older and the newer half of the window
        for (long k = 0; k < window_; ++k) {
          const int half = k < window_ / 2 ? 0 : 1;
          const long i = (step - window_ + k) % window_;
          v[half] += speed[i];
          w[half] += spin[i];
        }
        const double n = static_cast<double>(window_);
        done = (v[0] + v[1]) / n < v_tol && (w[0] + w[1]) / n < w_tol && v[1] <= v[0] + 1e-3 * v_tol * n &&
               w[1] <= w[0] + 1e-3 * w_tol * n;
      }
      timed += Clock::now() - s0;
      // Untimed: the deepest hull vertex below the wall.
      const btTransform& x = body_->getWorldTransform();
      const btVector3 row = x.getBasis().getRow(2);
      const double z0 = x.getOrigin().z();
      for (const Vec3& p : vertices_)
        out.max_depth = std::max(out.max_depth, -(z0 + row.x() * p.x() + row.y() * p.y() + row.z() * p.z()));
      if (done) {
        out.rested = true;
        out.slept = slept;
        break;
      }
    }
    out.max_depth /= units_;
    out.time = static_cast<double>(step) * dt_;
    out.seconds = std::chrono::duration<double>(timed).count();
    const btMatrix3x3& b = body_->getWorldTransform().getBasis();
    const Vec3 down_bullet(-b[2][0], -b[2][1], -b[2][2]);  // Bᵀ·(0,0,−1)
    out.down_body = axes_ * down_bullet;
    return out;
  }

 private:
  btDefaultCollisionConfiguration config_;
  btCollisionDispatcher dispatcher_;
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  btDiscreteDynamicsWorld world_;
  btStaticPlaneShape ground_shape_;
  std::unique_ptr<btRigidBody> ground_;
  btConvexHullShape hull_;
  std::unique_ptr<btRigidBody> body_;
  repose::Mat3 axes_;
  std::vector<Vec3> vertices_;  // Bullet's units
  double units_ = 1;            // Bullet's length units per metre
  bool sleep_ = true;
  double dt_ = 1e-3;   // the fixed step (s)
  long window_ = 100;  // the rest window in steps

 public:
  ~BulletSide() {
    world_.removeRigidBody(body_.get());
    world_.removeRigidBody(ground_.get());
  }
};

}  // namespace peer
