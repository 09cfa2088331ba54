// The pick of the packed vertices that can decide an event search (src/sim/phases/step_vertices.hpp): it
// keeps every vertex that can reach its event or hold the smallest margin in the interval, and drops the
// others — the whole point of the narrowing (contact_step_events.cpp). Heights here are z = offset.z (r3 = ẑ,
// base 0).
#include "sim/phases/step_vertices.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace repose::sim {
namespace {

constexpr double kSlack = 1e-12;

// A vertex at height z, a distance d from the pivot, that pierces below −1e-9 (no band events).
void add(StepVertices& v, double z, double d) {
  v.offset.emplace_back(0.0, 0.0, z);
  v.distance.push_back(d);
  v.pierce.push_back(-1e-9);
  v.rise.push_back(INFINITY);
  v.enter.push_back(-INFINITY);
}

std::vector<double> heights(const StepVertices& v) {
  std::vector<double> z;
  for (const Vec3& o : v.offset) z.push_back(o.z());
  return z;
}

// With no turn a margin is fixed: only the lowest vertex can hold the smallest margin, wherever it is in the
// packed list (first, middle, last), and the scratch left by an earlier, longer pick changes nothing.
TEST(StepVertices, WithoutTurnOnlyTheLowestDecides) {
  std::vector<double> scratch;
  StepVertices big, out;
  for (int k = 0; k < 6; ++k) add(big, -1.0 + 0.1 * k, 1.0);  // stale scratch: low values everywhere
  select_event_vertices(big, Vec3::UnitZ(), 0.0, 0.0, kSlack, scratch, out);
  for (const std::size_t lowest : {0u, 1u, 2u}) {
    StepVertices from;
    for (std::size_t k = 0; k < 3; ++k)
      add(from, k == lowest ? 0.001 : 1.0 + 0.5 * static_cast<double>(k), 1.0);
    select_event_vertices(from, Vec3::UnitZ(), 0.0, 0.0, kSlack, scratch, out);
    EXPECT_EQ(heights(out), std::vector<double>{0.001}) << "lowest at " << lowest;
  }
}

// A turn of θ moves a vertex at distance d by up to θ·d: the vertices whose margin can come within that of
// the lowest one's upper bound are kept, in their packed order; one a little above is dropped.
TEST(StepVertices, ATurnKeepsTheVerticesWithinReach) {
  std::vector<double> scratch;
  StepVertices from, out;
  add(from, 0.29, 1.0);  // m − θ·d = 0.19 ≤ keep 0.20: kept
  add(from, 0.10, 1.0);  // the lowest: m + θ·d = 0.20 is the bound
  add(from, 0.45, 2.0);  // 0.45 − 0.2 = 0.25 > 0.20: dropped
  add(from, 0.39, 2.0);  // 0.39 − 0.2 = 0.19: kept
  select_event_vertices(from, Vec3::UnitZ(), 0.0, 0.1, kSlack, scratch, out);
  EXPECT_EQ(heights(out), (std::vector<double>{0.29, 0.10, 0.39}));
}

}  // namespace
}  // namespace repose::sim
