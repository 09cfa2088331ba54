#include "contact_type.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace repose::sim {

LineFit fit_line(const std::vector<Vec3>& points) {
  LineFit fit;
  if (points.empty()) return fit;
  for (const Vec3& p : points) fit.centroid += p;
  fit.centroid /= static_cast<double>(points.size());
  // The six distinct sums of the symmetric scatter matrix (a full 3×3 outer product per point costs more,
  // and the fit runs on every contact decision).
  double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
  for (const Vec3& p : points) {
    const Vec3 d = p - fit.centroid;
    xx += d.x() * d.x();
    xy += d.x() * d.y();
    xz += d.x() * d.z();
    yy += d.y() * d.y();
    yz += d.y() * d.z();
    zz += d.z() * d.z();
  }
  Mat3 scatter;
  scatter << xx, xy, xz, xy, yy, yz, xz, yz, zz;
  if (xz == 0 && yz == 0 && zz == 0) {
    // Points in a plane z = const (the engine fits footprints on the wall every step): the 2×2 problem has a
    // closed form, [a b; b c] with eigenvalues m ± r. The eigenvector of the larger one is taken from
    // whichever of its two expressions has the larger norm, so it stays accurate for any orientation.
    const double a = scatter(0, 0), b = scatter(0, 1), c = scatter(1, 1);
    const double m = 0.5 * (a + c), r = std::hypot(0.5 * (a - c), b);
    const Vec2 u(b, m + r - a), v(m + r - c, b);
    const Vec2 dir = u.squaredNorm() >= v.squaredNorm() ? u : v;
    fit.direction = dir.squaredNorm() > 0 ? Vec3(dir.x(), dir.y(), 0).normalized() : Vec3::UnitX();
    fit.rss = std::max(0.0, m - r);
    return fit;
  }
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
