#include "contact.hpp"

#include <Eigen/Eigenvalues>

namespace repose::sim {

LineFit fit_line(const std::vector<Vec3>& points) {
  LineFit fit;
  if (points.empty()) return fit;
  for (const Vec3& p : points) fit.centroid += p;
  fit.centroid /= static_cast<double>(points.size());
  Mat3 scatter = Mat3::Zero();
  for (const Vec3& p : points) scatter += (p - fit.centroid) * (p - fit.centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(scatter);
  fit.direction = eig.eigenvectors().col(2).normalized();  // largest spread
  // Residual = total scatter minus the part along the line.
  fit.rss = std::max(0.0, eig.eigenvalues()(0) + eig.eigenvalues()(1));
  return fit;
}

ContactType classify_contact(const std::vector<Vec3>& points, double rss_threshold, LineFit* fit) {
  if (points.size() <= 1) return ContactType::point;
  const LineFit f = fit_line(points);
  if (fit) *fit = f;
  return f.rss < rss_threshold ? ContactType::line : ContactType::surface;
}

}  // namespace repose::sim
