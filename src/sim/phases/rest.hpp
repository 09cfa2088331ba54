// Internal: the phases that end a run — rest (a true static equilibrium: a hull face flush on the wall with
// the centre of mass above it, section 2.4) and stopped (the time or step limit).
#pragma once

#include <optional>
#include <vector>

#include "../body/dynamics.hpp"
#include "../run.hpp"

namespace repose::sim {

/// Where a particle rests: the hull face and the points it stands on.
struct RestPose {
  RestKind kind = RestKind::none;
  int face = -1;
  std::vector<Vec3> points;  ///< world coordinates of the face's vertices, on the wall
};

/// The hull face whose plane the vertical through the centre of mass meets first from below (of those facing
/// the wall, the one facing it most), the pose taken about `support`; −1 if none.
int face_under_com(const Run& run, const Support& support);

/// Finds the hull face under the centre of mass; if it is a statically stable face, turns the run's pose
/// about the support point so that the face is exactly flush on the wall, and returns the rest. Nothing
/// changes otherwise.
std::optional<RestPose> flush_rest(Run& run, const Support& support);

/// At rest: nothing moves.
struct Rest {
  RestPose pose;
  int contact_count = 0;  ///< the contact set's size when the rest was found
};

/// Stopped by a limit, with the motion it had then.
struct Stopped {
  Status why = Status::max_time;
  Vec3 omega = Vec3::Zero();
  int contact_count = 0;
  double kinetic_energy = 0;
  Vec3 velocity = Vec3::Zero();  ///< the centre of mass's, when it stopped
};

}  // namespace repose::sim
