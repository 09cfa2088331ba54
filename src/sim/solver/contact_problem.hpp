// Internal: the frictional contact problem of a rigid body touching the wall z = 0 at several points, at the
// velocity level (impulses: multi_impact.cpp) or at the acceleration level (forces: contact_forces.cpp).
//
// Each point i (offset r_i from the centre of mass) has a value x_i = lin + ang × r_i + offset_i, the
// point's velocity (lin, ang: the body's velocity and angular velocity) or its acceleration (lin, ang: the
// body's linear and angular accelerations; offset: the centripetal part ω × (ω × r_i)). A reaction R_i at the
// point changes lin by R_i/m and ang by I⁻¹ (r_i × R_i). The rule of each point:
//   unilateral    R_n ≥ 0, x_n ≥ 0, R_n·x_n = 0; the point sticks (x_t = 0, |R_t| ≤ μ·R_n) or slides
//                 (R_t = −μ·R_n·ŝ with ŝ the direction of x_t): Coulomb's law, with the direction found.
//   sliding       the point slides along a given ŝ: R_t = −μ·R_n·ŝ, R_n ≥ 0, x_n ≥ 0, complementary. Where
//                 W_nn − μ·W_nt·ŝ ≤ 0 (friction would drive the point into the wall faster than the normal
//                 reaction lifts it) and the point approaches, there is no consistent R_n (Painlevé): R_n = 0
//                 and the case is counted.
//   given_normal  R_n is given; R_t sticks if the cone μ·R_n allows, else slides (restitution).
// Solved by block Gauss–Seidel over the points, each block exactly, until a sweep changes no point's value by
// more than 1e-14 of the problem's scale: the values are then determined even where the reactions are not
// (a face's four corners share three constraints). With sliding friction and μ above about 1 the sweeps need
// not contract; where they diverge or do not converge, the problem is solved as one LCP by Lemke's method.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "../body/kinematics.hpp"
#include "point_list.hpp"
#include "repose/geometry/types.hpp"

namespace repose::sim {

enum class PointRule { unilateral, sliding, given_normal };

struct PointCondition {
  PointRule rule = PointRule::unilateral;
  Vec2 direction = Vec2::Zero();  ///< sliding: ŝ, a unit vector
  double normal = 0;              ///< given_normal: R_n
};

struct ContactProblem {
  double mass = 1;
  Mat3 inverse_inertia = Mat3::Identity();  ///< world frame
  PointList<Vec3> arms;                     ///< r_i
  PointList<Vec3> offsets;                  ///< empty: none
  double friction = 0;                      ///< μ, finite
  double scale = 1;                         ///< of the values, for the tolerances
};

struct ContactSolution {
  PointList<Vec3> reactions;
  Vec3 lin = Vec3::Zero(), ang = Vec3::Zero();  ///< with the reactions
  /// Within the sweep bound, and every sliding direction found (where one was not, not met in the tests, the
  /// point took the frictionless plastic reaction).
  bool converged = true;
  /// False where neither Gauss–Seidel nor Lemke's method reached a solution (the reactions are then not
  /// usable: Painlevé's case or a problem with no solution).
  bool solved = true;
  int painleve = 0;  ///< sliding points with no consistent normal reaction
  /// Lemke's pyramid answer kept (Newton's method did not make it exact): friction at points at rest up to
  /// 15° off their slip and 3.4 % short of the cone. Counted by the run (a fallback).
  bool pyramid = false;
};

/// The reactions from the body's state (lin, ang) without them. The sweeps start from `start`'s reactions if
/// it has one per point (a nearby problem's: warm-started), else from none.
ContactSolution solve_contacts(const ContactProblem& problem, const Vec3& lin, const Vec3& ang,
                               std::span<const PointCondition> conditions, std::span<const Vec3> start = {});

/// The same as one linear complementarity problem solved by Lemke's method (solve_contacts' fallback where
/// Gauss–Seidel does not converge): a point at rest has a friction pyramid of 12 edges (its force falls short
/// of the cone by at most 3.4 %, exact along x and y). Empty on a given normal reaction, or where the problem
/// has no solution Lemke's method reaches (Painlevé's cases).
std::optional<ContactSolution> solve_contacts_by_pivoting(const ContactProblem& problem, const Vec3& lin,
                                                          const Vec3& ang,
                                                          std::span<const PointCondition> conditions);

/// Newton's method on the problem's Alart–Curnier equations from the reactions `start` (solve_contacts'
/// polish where Gauss–Seidel creeps): the reactions it reached, a solution or the best it found. Empty where
/// the data are not finite.
std::optional<PointList<Vec3>> solve_contacts_by_newton(const ContactProblem& problem, const Vec3& lin,
                                                        const Vec3& ang,
                                                        std::span<const PointCondition> conditions,
                                                        std::span<const Vec3> start);

/// One point's sliding reaction R = (−μ·λ·ŝ, λ) on the edge of its friction cone, with its slip after it
/// (x = f + W·R, `f` its value without it, W its Delassus block) along ŝ: a root of the secular equation
/// (contact_problem.cpp). `given_normal` < 0: the point is unilateral (x_n = 0 after it); else λ is given.
/// Called where sticking would leave the cone. Empty where the data are not finite (or λ would be < 0).
std::optional<Vec3> sliding_reaction(const Mat3& W, const Vec3& f, double mu, double given_normal);

/// A sliding point's normal compliance under its own friction: how much its normal acceleration grows per
/// unit of its normal force when that force carries −μ·ŝ of it along the wall, W_nn − μ·W_nt·ŝ (W its
/// Delassus block, body/kinematics.hpp; ŝ its slip's direction). Painlevé's case where it is ≤ 0: its own
/// force drives it in.
double sliding_compliance(const Mat3& W, double mu, const Vec2& direction);

/// The value x_i of point i for (lin, ang). Inline: the sweeps take it several times per point and sweep.
inline Vec3 point_value(const ContactProblem& p, std::size_t i, const Vec3& lin, const Vec3& ang) {
  Vec3 x = lin + ang.cross(p.arms[i]);
  if (!p.offsets.empty()) x += p.offsets[i];
  return x;
}

}  // namespace repose::sim
