// Internal: the impact phase — what happens when an airborne particle reaches the wall with rigid-body
// impacts (issue 14: Stronge's restitution and Coulomb friction, rigid_impact.hpp). It takes no time: the
// impacts at the points on the wall are resolved in turn, and they end in a rebound (a new flight) or hand
// over to the contact phase with the angular momentum they left (docs/method.md, "Rebound").
#pragma once

#include <vector>

#include "../rigid_impact.hpp"
#include "../run.hpp"

namespace repose::sim {

class Impact {
 public:
  explicit Impact(Run& run);

  struct Outcome {
    bool rebound = false;  ///< every point on the wall leaves it: a flight follows
    Motion motion;         ///< the centre of mass's velocity and the angular velocity after the impacts
  };
  /// Resolves the impacts of the particle at the run's pose arriving with `motion`; each is recorded.
  Outcome resolve(const Motion& motion);

 private:
  Run& run_;
  ImpactLaw law_;
  std::vector<Vec3> arms_;         // centre of mass → the vertices on the wall
  std::vector<Vec3> approaching_;  // those of them moving into the wall
};

}  // namespace repose::sim
