// The contact forces, solved at every evaluation of a frictional segment's rates, allocate nothing for up to
// tol::kInlinePoints points (issue 49: no allocation in a step; src/sim/solver/point_list.hpp). This binary's
// global operator new counts the allocations of the thread that calls it; each test checks first that the
// count sees an allocation, so a counter that was not linked in fails it instead of passing it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <new>
#include <vector>

#include "sim/solver/contact_forces.hpp"

namespace {
thread_local long g_allocations = 0;
}  // namespace

// The replacement operator new is malloc, so its delete is free; GCC, inlining delete where it knows only the
// standard new, would call that a mismatch.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace repose::sim {
namespace {

constexpr double g = 9.81;

// A box 1 × 1 × 1 of mass 1 on its bottom face: its four bottom corners.
ContactBody unit_box() { return {1.0, Vec3(1.0 / 6, 1.0 / 6, 1.0 / 6).asDiagonal(), g, 0.0}; }
std::vector<Vec3> bottom_corners() {
  std::vector<Vec3> corners;
  for (double x : {-0.5, 0.5})
    for (double y : {-0.5, 0.5}) corners.emplace_back(x, y, -0.5);
  return corners;
}

// The allocations `solve` makes on its 2nd to 101st call (the first may warm up nothing but is not counted).
template <class Solve>
long allocations_of(Solve&& solve) {
  solve();
  const long before = g_allocations;
  for (int k = 0; k < 100; ++k) solve();
  return g_allocations - before;
}

// A volatile sink: the allocations below must happen, not be optimised away.
double* volatile g_sink = nullptr;

TEST(SolverAllocations, TheCounterSeesAnAllocation) {
  const long counted = allocations_of([] {
    std::vector<double> v(3);
    g_sink = v.data();
  });
  EXPECT_EQ(counted, 100);
}

// At rest on its face (four unilateral corners: the block Gauss–Seidel sweeps), warm-started from its own
// forces as a segment's rates are: no allocation, and the forces hold the weight.
TEST(SolverAllocations, AFaceAtRestAllocatesNothing) {
  const ContactBody body = unit_box();
  const std::vector<Vec3> arms = bottom_corners();
  const std::vector<PointCondition> resting(arms.size());
  const ContactForces first = contact_forces(body, {Vec3::Zero(), Vec3::Zero()}, arms, 0.5, resting);
  const std::vector<Vec3> warm(first.forces.begin(), first.forces.end());
  double normal = 0;
  const long counted = allocations_of([&] {
    const ContactForces f = contact_forces(body, {Vec3::Zero(), Vec3::Zero()}, arms, 0.5, resting, warm);
    normal = 0;
    for (const Vec3& force : f.forces) normal += force.z();
  });
  EXPECT_EQ(counted, 0);
  EXPECT_NEAR(normal, g, 1e-12 * g);  // m·g, to the solver's 1e-14 of the scale and a few sums
}

// Sliding flat (four sliding corners: the sliding face's own system) and an edge sliding on two corners while
// the body turns (Gauss–Seidel with sliding rules): no allocation.
TEST(SolverAllocations, SlidingContactsAllocateNothing) {
  const ContactBody body = unit_box();
  const std::vector<Vec3> face = bottom_corners();
  EXPECT_EQ(allocations_of([&] {
              contact_forces(body, {Vec3(1, 0, 0), Vec3::Zero()}, face, 0.3, 1e-12);
            }),
            0);
  const std::vector<Vec3> edge{Vec3(-0.5, -0.5, -0.5), Vec3(-0.5, 0.5, -0.5)};
  EXPECT_EQ(allocations_of([&] {
              contact_forces(body, {Vec3(0.5, 0, 0), Vec3(0, 1, 0)}, edge, 0.3, 1e-12);
            }),
            0);
}

}  // namespace
}  // namespace repose::sim
