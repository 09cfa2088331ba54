// Flat faces in `--vary vertices`: a hull face of four or more vertices is a kink of the probabilities
// (moving one of its vertices off its plane folds it one way or the other, with different one-sided
// derivatives), so the design keeps such faces flat. To first order each step stays on the faces' planes
// (constraint rows in the step's solve, design_step.cpp); after it the points are put back on them exactly
// (Gauss–Newton, the least move), so the hull keeps the face whole and the next gradient is its true
// derivative.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "repose/geometry/hull.hpp"
#include "repose/geometry/types.hpp"

namespace repose::detail {

// A face kept flat: its points (design-variable indices), three of them spanning its plane first (the widest
// triangle), the others each one constraint: its distance from their plane.
using FlatFace = std::vector<int>;

// The faces of four or more vertices of `hull` (the start's: its vertex v is design point v).
std::vector<FlatFace> flat_faces(const ConvexHull& hull);

// Those of `faces` that are faces of `hull` (the same points; hull vertex v is design point design_index[v]).
std::vector<FlatFace> standing_faces(const std::vector<FlatFace>& faces, const ConvexHull& hull,
                                     const std::vector<int>& design_index);

// The constraints' rows over the design variables (3 per point, `columns` in all): the gradient of each
// non-spanning point's distance from the plane of its face's spanning three.
Eigen::MatrixXd flatness_rows(const std::vector<FlatFace>& faces, const std::vector<Vec3>& points,
                              Eigen::Index columns);

// Moves `points` the least (Gauss–Newton on the constraints, a bounded number of rounds) until every face is
// flat to `tolerance`; false if that is not reached.
bool flatten(std::vector<Vec3>& points, const std::vector<FlatFace>& faces, double tolerance);

}  // namespace repose::detail
