// Internal: the impact phase — what happens when an airborne particle reaches the wall with rigid-body
// impacts (issue 14: Stronge's restitution and Coulomb friction, rigid_impact.hpp). It takes no time: the
// impacts at the points on the wall are resolved in turn, and they end in a rebound (a new flight) or hand
// over to the contact phase with the angular momentum they left (docs/method.md, "Rebound").
#pragma once

#include <vector>

#include "../impact/rigid_impact.hpp"
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
  /// The same at the given points on the wall (offsets from the centre of mass) with the given law (the
  /// frictional contact phase: its own contact band, and plastic touches too slow to leave it). With
  /// `every_point`, one point approaching among several on the wall takes the multi-point law with all of
  /// them (a point at rest on the wall is pushed into it too), not the one-point law alone.
  Outcome resolve(const Motion& motion, const std::vector<Vec3>& arms, const ImpactLaw& law,
                  bool every_point = false);

 private:
  Run& run_;
  ImpactLaw law_;
  std::vector<Vec3> arms_;         // centre of mass → the vertices on the wall
  std::vector<Vec3> approaching_;  // those of them moving into the wall
};

}  // namespace repose::sim
