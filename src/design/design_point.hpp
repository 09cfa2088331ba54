// A design point (design.cpp): the shape's points or planes and the centre of mass, evaluated (a new hull,
// particle and exact landscape, its outcomes' probabilities and the objective); the trial points a step
// gives, within the bounds; and the outcomes' Jacobian over the design variables (the tape).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "flat_faces.hpp"
#include "repose/design/design.hpp"
#include "repose/design/target.hpp"
#include "repose/model/particle.hpp"
#include "repose/poses/landscape.hpp"

namespace repose::detail {

// One design point, evaluated. Frame: the start's body frame (its centre of mass at the origin).
struct Point {
  std::vector<Vec3>
      points;  // the shape's points (vertices: one per start vertex; faces: the planes' vertices)
  std::vector<Vec3> planes;  // faces: p_f (face_planes.hpp)
  Vec3 com = Vec3::Zero();
  Vec3 centroid = Vec3::Zero();  // the solid hull's
  Particle particle;             // body frame: points − com
  // Per particle hull vertex: its design point (the particle's own indices count only the points on the
  // hull, so they shift once a point falls inside it).
  std::vector<int> design_index;
  RestLandscape landscape;
  DesignTarget target;
  // Per outcome (× L): the stability margin its best face is drawn to (attraction.hpp): DesignOptions::
  // min_margin, or 0 for an outcome with a stable face that starts closer to the edge than that.
  std::vector<double> margin_floor;
  std::vector<double> achieved;
  // Per outcome: its attraction residual (attraction.hpp; 0 unless all its faces are unstable).
  std::vector<double> attraction;
  // Σ (achieved − target)² over the outcomes and the unassigned faces, plus Σ attraction².
  double objective = 0, max_error = 0;
  std::set<std::pair<int, int>> stable;  // (outcome, count) of stable faces: the structure's coarse summary
};

struct Bounds {
  double com_margin, max_move, min_edge, min_area;  // lengths and an area
  std::vector<Vec3> origin;                         // where each vertex (faces: each plane's foot) started
  std::vector<FlatFace> flat;                       // vertices: faces kept flat (flat_faces.hpp)
};

inline Vec3 foot(const Vec3& plane) {
  return plane / plane.squaredNorm();
}  // the plane's point nearest the origin

// The centre of mass pushed along the most violated face normal until it is `margin` inside every face of
// `hull` (a bounded number of rounds); false if it is not.
bool push_inside(const ConvexHull& hull, double margin, Vec3& com);
double shortest_edge(const ConvexHull& hull);
double smallest_face(const ConvexHull& hull);

// The point with these shape points (planes: faces mode) and centre of mass (the start's body frame);
// `hull`, if given, is the points' hull (computed otherwise); `margin_floor`, if given, the outcomes'
// (options.min_margin for each otherwise).
Point evaluate(std::vector<Vec3> points, std::vector<Vec3> planes, const Vec3& com, const std::string& name,
               const DesignTarget& target, const DesignOptions& options, const ConvexHull* hull = nullptr,
               const std::vector<double>* margin_floor = nullptr);

// The point's outcomes' probabilities, stable faces per outcome and objective, from its landscape and its
// target (whose faces are assigned).
void score(Point& p);

// Per outcome (× L): the best stability margin among its faces (negative: none is stable).
std::vector<double> outcome_margins(const Point& p);

// The outcomes' (then the unassigned faces') probabilities' Jacobian over the design variables: 3 per shape
// variable (a design vertex, zero for one not on the hull; or a plane), then the centre of mass's 3.
Eigen::MatrixXd jacobian(const Point& p, MassModel mass, ShapeFreedom shape);

// Rows over the hull's vertices (3j + k, body frame) and the centre of mass (3) to rows over the design
// variables (jacobian()'s columns).
Eigen::MatrixXd design_columns(const Point& p, const Eigen::MatrixXd& rows, ShapeFreedom shape);

// The trial point `d` (unscaled: shape variables, then the centre of mass) away from `at`, the shape within
// its move bound and the centre of mass pushed inside the shrunk hull; nothing (counted in `step`) if a
// bound cannot hold or the shape degenerates. `moved`: the largest move.
std::optional<Point> trial_point(const Point& at, const Eigen::VectorXd& d, MassModel mass,
                                 ShapeFreedom shape, const Bounds& bounds, const std::string& name,
                                 const DesignTarget& target, const DesignOptions& options, DesignStep& step,
                                 double& moved);

}  // namespace repose::detail
