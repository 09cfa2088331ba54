// Inverse design (issue 50, `repose design`): the centre of mass and/or the convex hull's vertices that give
// a target probability per outcome under quasi-static rolling (docs/inverse-design.md).
#pragma once

#include <string>
#include <vector>

#include "repose/design/basin_gradient.hpp"
#include "repose/design/target.hpp"
#include "repose/geometry/types.hpp"
#include "repose/model/particle.hpp"

namespace repose {

/// How the shape may change: not at all, vertex by vertex (a scanned grain's triangulated hull: its faces
/// then fold), or plane by plane (a die's flat faces stay flat; its vertices are the planes' intersections).
enum class ShapeFreedom { none, vertices, faces };

/// What the design may change.
struct DesignFreedom {
  bool center_of_mass = true;
  ShapeFreedom shape = ShapeFreedom::vertices;
};

/// A '+'-separated list of "center-of-mass" and one of "vertices" or "faces" (e.g. "faces+center-of-mass");
/// throws repose::Error naming the accepted values otherwise.
DesignFreedom parse_design_freedom(const std::string& text);

struct DesignOptions {
  DesignFreedom freedom;
  /// With moving vertices: the centre of mass follows the solid's centroid (plus its offset, an insert that
  /// moves with the part) or stays fixed in the body frame.
  MassModel mass = MassModel::follows_shape;
  double outcome_angle = 0.5;  ///< rad: a hull face belongs to the nearest outcome normal within this
  /// After every accepted step each outcome's normal becomes that of its most probable stable face, and the
  /// faces are assigned afresh (convex_dice's rule: an outcome is the face the die shows, wherever the design
  /// turns it). False: the target's normals stay fixed in the body frame.
  bool follow_outcome_normals = false;
  double com_margin = 0.05;       ///< × L: the centre of mass stays at least this far inside every face
  double max_vertex_move = 0.15;  ///< × L: no vertex (faces: no plane's foot from the start's centre of mass)
                                  ///< moves further than this from where it started
  double min_edge = 0.02;       ///< × L: no hull edge gets shorter (unless it started shorter)
  double min_face_area = 1e-3;  ///< × L²: no hull face gets smaller (unless it started smaller)
  /// × L: every outcome (target > 0) is drawn toward a stable face whose centre-of-mass projection lies at
  /// least this far inside it (a residual in the objective; 0: only an outcome with no stable face is),
  /// unless its best face starts stable and closer to the edge than this (then only kept stable).
  double min_margin = 0;
  /// Vertices: the start's faces of four or more vertices stay flat (each is a kink of the probabilities
  /// otherwise: moving one vertex folds it one way or the other). False lets them fold.
  bool keep_faces_flat = true;
  double max_step = 0.05;  ///< × L: the most any shape variable moves in one iteration (a trust region)
  /// × L: shape steps are smooth over about this distance (a Sobolev metric; 0: every variable on its own).
  double smoothing = 0.1;
  double tolerance = 1e-4;   ///< done when every outcome is within this of its target
  int max_iterations = 200;  ///< Levenberg–Marquardt iterations, each one exact gradient
  int max_trials = 16;       ///< trial steps per iteration before it stalls
};

/// One iteration of the optimiser.
struct DesignStep {
  /// Σ (achieved − target)² over the outcomes and the unassigned faces, plus the squared attraction of any
  /// outcome whose faces are all unstable (docs/inverse-design.md, "Outcomes that cannot start")
  double objective = 0;
  double max_error = 0;            ///< max |achieved − target|
  double step = 0;                 ///< largest vertex or centre-of-mass move of the accepted step (× L)
  int stable_faces = 0;            ///< of the hull after the step
  int trials = 0;                  ///< trial steps tried; the rejected ones by why:
  int rose = 0;                    ///<   the objective did not fall (a smaller step is tried next)
  int unprintable = 0;             ///<   an edge or a face below its minimum
  int com_outside = 0;             ///<   the centre of mass could not be kept com_margin inside the hull
  int degenerate = 0;              ///<   the points' hull degenerated
  bool structure_changed = false;  ///< the set of stable faces changed (a topology change of the basins)
  /// follow_outcome_normals: the normals moved to their faces' and some face changed outcome with them
  bool outcomes_reassigned = false;
  /// follow_outcome_normals: the normals were not moved (an outcome would have lost all its faces)
  bool normals_kept = false;
  bool accepted = false;  ///< a trial step lowered the objective (the last iteration of a stalled design: no)
};

struct DesignResult {
  std::vector<Vec3> vertices;  ///< the design's hull vertices, the input mesh's frame
  TriangleMesh mesh;           ///< the design's hull, triangulated, outward-wound, the input mesh's frame
  Vec3 center_of_mass;         ///< the input mesh's frame
  Vec3 centroid;               ///< the design solid's centroid (where a uniform part has its centre of mass)
  double length = 0;           ///< L of the design
  std::vector<double> target;  ///< per outcome, then the unassigned faces (0)
  /// Per outcome: the normal its faces are assigned by at the design (the target's, unless
  /// follow_outcome_normals moved it), the input mesh's frame.
  std::vector<Vec3> outcome_normals;
  /// Per outcome (× L): the best stability margin among its faces at the design (how far the centre of
  /// mass's projection lies inside the face; negative: no face of it is stable).
  std::vector<double> outcome_margin;
  std::vector<double> start;     ///< the same, achieved by the starting body
  std::vector<double> achieved;  ///< the same, by the design (exact quasi-static basins)
  std::vector<DesignStep> history;
  std::string stop;  ///< "converged", "iterations" (max_iterations reached) or "stalled" (no trial step
                     ///< lowered the objective within the bounds: the best achievable from here)
  bool reached() const { return stop == "converged"; }
  double max_error() const;
};

/// Designs from `start` (its hull and centre of mass) toward `target` (outcomes assigned afresh to the
/// changing hull's faces every iteration). Levenberg–Marquardt on the outcomes' residuals with their exact
/// Jacobian (basin_gradient.hpp); a step is kept only if the objective falls and every bound holds (the rule
/// at topology changes: the current structure's gradient, the true objective to accept). Throws repose::Error
/// for options out of range or a target normal that is no outcome of the starting hull.
DesignResult design_quasi_static(const Particle& start, DesignTarget target,
                                 const DesignOptions& options = {});

}  // namespace repose
