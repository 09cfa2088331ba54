// The linear algebra of a design step (design.cpp): the shape's Sobolev metric and the Levenberg–Marquardt
// step with its move bounds as an active set.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <memory>

#include "design_point.hpp"

namespace repose::detail {

using Metric = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>;

// The shape's metric M = I + αΛ (see design_step.cpp); nothing for the identity (no shape, smoothing 0).
std::unique_ptr<Metric> shape_metric(const Point& at, ShapeFreedom shape, double smoothing, double length);

// M⁻¹ applied to the shape rows of `t` (variables × columns; the centre of mass's last 3 rows untouched).
Eigen::MatrixXd apply_inverse(const Metric* metric, Eigen::MatrixXd t);

// The Levenberg–Marquardt step in scaled (dimensionless) variables (see design_step.cpp).
Eigen::VectorXd lm_step(Eigen::MatrixXd jac, const Eigen::VectorXd& residual, double lambda, const Point& at,
                        const Bounds& bounds, ShapeFreedom shape, double length, const Metric* metric);

}  // namespace repose::detail
