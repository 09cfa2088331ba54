// Internal: the support a particle turns about right after an impact leaves several of its hull vertices on
// the wall (docs/method.md, "Rotation about a point and a line"). The impact is perfectly inelastic: angular
// momentum about the new support is conserved (dynamics.hpp, momentum_after_switch), and the new support must
// let every other point on the wall lift off, or the rigid body would be pushed through the wall.
#pragma once

#include <vector>

#include "../body/dynamics.hpp"

namespace repose::sim {

/// A hull vertex on the wall (within the touching tolerance; Flight::Touch is the motion when one reaches
/// it): its index, where it is, and its height (which may differ from world.z() by round-off; the engine's
/// own height of the vertex).
struct WallVertex {
  int vertex = -1;
  Vec3 world = Vec3::Zero();
  Vec3 body = Vec3::Zero();  ///< body frame, relative to the centre of mass
  double height = 0;
};

/// The particle just before the impact, and the scales the tolerances are relative to.
struct SwitchState {
  const Body& body;
  Quat q;
  Vec3 com;
  Vec3 omega;            ///< angular velocity just before
  Vec3 com_velocity;     ///< centre-of-mass velocity just before
  double length = 0;     ///< L
  double touch_tol = 0;  ///< a vertex this close to the wall is touching it (1e-9·L)
  double dt = 0;         ///< the time step: a point pulled back within a tenth of it does not separate
};

/// A support with the hull vertex that is its point.
struct SupportChoice {
  Support support;
  int vertex = -1;
  /// The impact leaves no motion: every support the motion could go on about would drive another touching
  /// point into the wall, so the approaching points are struck together, plastically, which stops a body
  /// with three or more points on the wall (no normal velocity at three points leaves none); the support
  /// then starts from rest.
  bool stop = false;
};

/// The support at hull vertex `t` (a point), or the horizontal line through it along `axis` (its z is
/// dropped: the line joins two points on the wall).
SupportChoice point_support(const WallVertex& t);
SupportChoice line_support(const WallVertex& t, Vec3 axis);

/// Whether, rotating about `next` right after the impact (angular momentum about it conserved), every other
/// touching point moves up, or at zero speed is accelerated up by gravity, and is not pulled back within a
/// tenth of a step.
bool others_separate(const SwitchState& impact, const std::vector<WallVertex>& touching, const Support& next);

/// Several points on the wall, centre of mass's projection `g`: the feature of their polygon nearest `g`,
/// unless that would drive another touching point into the wall; then the first feature (edges in polygon
/// order, then corners) that lets every other point separate. Failing that, the motion stops (`stop`) and
/// the same search is made from rest, where gravity alone decides; failing that too (the centre of mass over
/// the polygon), the nearest edge from rest, which keeps both its ends on the wall.
SupportChoice choose_from_touching(const SwitchState& impact, const std::vector<WallVertex>& touching,
                                   const Vec2& g);

/// A smooth particle turns about its single lowest point: the lowest touching point other than the current
/// support's vertex `current` (the most recent touch; of equal heights the first listed), else that vertex;
/// if that would drive another touching point into the wall (rocking on an edge of the discretised surface),
/// as choose_from_touching.
SupportChoice choose_smooth(const SwitchState& impact, const std::vector<WallVertex>& touching,
                            const WallVertex& current, const Vec2& g);

}  // namespace repose::sim
