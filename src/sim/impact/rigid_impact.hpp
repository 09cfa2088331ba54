// Internal: a rigid body striking the wall z = 0 (issue 14's rebound; docs/method.md, "Rebound").
//
// One point: the impulse is integrated along the normal impulse p as the independent variable, in the
// manner of Routh, Keller and Stronge (Stronge, Impact Mechanics, 2nd ed., 2018, ch. 5). The contact
// point's velocity is linear in the impulse P: u(P) = u₀ + K·P with K = 1/m − [r]× I⁻¹ [r]×. Friction is
// Coulomb's: while the point slides, dP_t/dp = −μ·ŝ (ŝ the sliding direction, which may turn); when sliding
// stops it sticks if the ratio that keeps it stuck, |K_tt⁻¹ K_tn|, is at most μ, else it slides again in the
// one direction in which the tangential velocity grows (slip reversal in a plane). Compression ends where the
// normal velocity is zero; restitution ends where the normal impulse's work in it is E² times minus its work
// in compression (Stronge's energetic coefficient E), so no impact creates energy, with or without friction.
// Several points landing at once: the impact of a frictionless, perfectly plastic contact at every point (a
// linear complementarity problem, Moreau's) gives the impulses' centre, where the one-point law above acts.
#pragma once

#include <cmath>
#include <optional>
#include <vector>

#include "../body/kinematics.hpp"
#include "repose/geometry/types.hpp"

namespace repose::sim {

struct ImpactLaw {
  double restitution = 0;      ///< Stronge's energetic coefficient E in [0, 1]
  double friction = INFINITY;  ///< Coulomb's μ ≥ 0; infinite: the point never slides
};

struct ImpactOutcome {
  Motion after;
  Vec3 impulse = Vec3::Zero();       ///< on the body at the point, world frame
  Vec3 speed_before = Vec3::Zero();  ///< the contact point's velocity just before
  Vec3 speed_after = Vec3::Zero();   ///< and just after
  bool stick = false;                ///< the point was not sliding at the end of the impact
  bool fallback = false;  ///< the frictional integration did not end (see rigid_impact.cpp): frictionless
};

/// The body (mass m, inertia `inertia` about the centre of mass in the world frame) moving with `before`
/// strikes the wall at the point `r` from its centre of mass. If the point is not approaching the wall the
/// motion is returned unchanged.
ImpactOutcome collide(double mass, const Mat3& inertia, const Vec3& r, const Motion& before,
                      const ImpactLaw& law);

/// Several points (offsets `r` from the centre of mass) on the wall at once: the centre of the normal
/// impulses of a frictionless perfectly plastic impact at all of them (projected Gauss–Seidel on Moreau's
/// complementarity problem), as an offset from the centre of mass; none if no point approaches the wall.
std::optional<Vec3> impulse_centre(double mass, const Mat3& inertia, const std::vector<Vec3>& r,
                                   const Motion& before);

}  // namespace repose::sim
