// Internal: several points of a rigid body striking the wall at once, with Coulomb friction at each of them
// (a face or an edge landing flat; docs/method.md, "Rebound").
//
// Compression is Moreau's perfectly plastic impact with Coulomb friction at every point, at the velocity
// level: impulses P_i = (P_t, λ) with λ ≥ 0, the normal velocity after u_n ≥ 0 and λ·u_n = 0; each point
// sticks (u_t = 0, |P_t| ≤ μ·λ) or slides (P_t = −μ·λ·ŝ, ŝ its sliding direction after). Solved by block
// Gauss–Seidel over the points, each block exactly (stick, or the sliding fixed point). Restitution is
// Poisson's at each point, E times its compression normal impulse, with friction again within μ times it;
// should that raise the kinetic energy above what the body had before (friction and Poisson's rule can, in
// rare configurations), the restitution's normal impulses are halved, with friction solved again, until it
// does not. A compression without a solution, or one gaining kinetic energy (an exact one cannot), is the
// frictionless plastic impact instead, flagged not converged.
//
// One point alone keeps Stronge's law (rigid_impact.hpp): along the impulse, exact. Several points get the
// friction of each of them, which the impulses' centre cannot give: a spinning face landing flat loses spin
// to torsional friction, and a face landing while sliding does not pitch.
#pragma once

#include <vector>

#include "rigid_impact.hpp"

namespace repose::sim {

struct MultiImpactOutcome {
  Motion after;
  std::vector<Vec3> impulses;     ///< on the body at each point, world frame
  std::vector<Vec3> speed_after;  ///< each point's velocity just after
  bool converged = true;          ///< Gauss–Seidel met its tolerance within its sweep bound
};

/// The body (mass, inertia about the centre of mass in the world frame) moving with `before` strikes the
/// wall at the points `arms` (offsets from the centre of mass, all on the wall). Points not approaching it
/// take no impulse unless the others' impulses push them into it. μ must be finite.
MultiImpactOutcome collide_points(double mass, const Mat3& inertia, const std::vector<Vec3>& arms,
                                  const Motion& before, const ImpactLaw& law);

}  // namespace repose::sim
