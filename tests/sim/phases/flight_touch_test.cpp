// The touch that ends a spinning flight (sim::Flight::locate_touch) is the first instant in the flight
// step at which a hull vertex reaches the wall. Oracle, computed here from the flight's own motion (the
// centre of mass on its parabola, the orientation from the integrator's dense output): a scan of the step at
// 4,000 instants finds no vertex below the wall before the located touch, and at the touch the lowest vertex
// is on the wall. White box: the engine (sim::Engine) is driven step by step through tossed drops of
// irregular grains with lively rebounds (E = 0.9), which make many short flights, each starting where an
// impact ended.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <repose/model/particle.hpp>
#include <repose/poses/sampling.hpp>
#include <string>
#include <vector>

#include "../../../src/sim/engine.hpp"

namespace repose {
namespace {

// The lowest hull vertex's height at time s of the flight step just taken.
double lowest_height(const Particle& p, const sim::Flight& f, double t) {
  const Quat q = f.rotation().orientation_at(t);
  const double zc = f.centre_at(t).first;
  double lowest = std::numeric_limits<double>::infinity();
  for (const Vec3& v : p.hull.vertices) lowest = std::min(lowest, zc + (q * v).z());
  return lowest;
}

TEST(FlightTouch, IsTheFirstInstantAVertexReachesTheWall) {
#ifdef NDEBUG
  constexpr int kDrops = 6;
#else
  constexpr int kDrops = 3;  // the sanitizer build is ~10x slower
#endif
  constexpr int kScan = 1000;
  long steps_checked = 0, touches = 0;
  for (const char* spec : {"irregular:seed=3", "irregular:seed=5"}) {
    const Particle p = load_particle(spec, 1000.0);
    const double L = p.length, g = 9.81;
    SettleParams params;
    params.restitution = 0.9;
    params.friction = 0.6;
    params.drop_height = 4 * L;
    params.damping = 0.05 * p.mass.mass * std::sqrt(g * L * L * L);
    for (int drop = 0; drop < kDrops; ++drop) {
      // Half the drops barely spin: the bound on a vertex's acceleration is then nearly gravity's, tight.
      const double spin_max = (drop % 2 ? 1e-3 : 1.5) * std::sqrt(g / L);
      const Toss toss = drop_toss(1, static_cast<std::uint64_t>(drop), {1.5 * std::sqrt(g * L), spin_max});
      params.velocity = toss.velocity;
      params.spin = toss.spin;
      sim::Engine engine(p, params, drop_orientation(1, static_cast<std::uint64_t>(drop)));
      for (int step = 0; step < 200000 && engine.status() == Status::running; ++step) {
        // The flight's next integrator step taken here, as the flight phase takes it, so that its located
        // touch can be checked before the engine acts on it (the engine then goes on from this step).
        auto* f = std::get_if<sim::Flight>(&engine.phase());
        if (f != nullptr && f->spinning() && engine.run().t >= f->step_end()) {
          const auto [a, b] = f->integrate_step();
          const double touch = f->located_touch(), end = std::min(touch, b);
          const std::string what = std::string(spec) + " drop " + std::to_string(drop) + " step [" +
                                   std::to_string(a) + ", " + std::to_string(b) + "]";
          for (int i = 0; i < kScan; ++i) {
            const double t = a + (end - a) * i / kScan;
            ASSERT_GE(lowest_height(p, *f, t), -1e-12 * L)
                << what << ": below the wall at " << t << " < " << touch;
          }
          ++steps_checked;
          if (touch <= b) {
            ++touches;
            // Located to 2^-44 of the step: at the flight's speeds, far below 1e-9·L of height.
            EXPECT_LE(std::abs(lowest_height(p, *f, touch)), 1e-9 * L)
                << what << ": no vertex on the wall at " << touch;
          }
        }
        engine.step();
      }
      EXPECT_EQ(engine.status(), Status::rest);
    }
  }
  // Measured: 4,682 flight steps, 166 of them ending at a touch.
  EXPECT_GT(touches, 100);
  EXPECT_GT(steps_checked, touches);
}

}  // namespace
}  // namespace repose
