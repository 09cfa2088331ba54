// A face sliding flush on the wall (sliding_face.hpp).
#include "sliding_face.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "../tolerances.hpp"

namespace repose::sim {

namespace {

// Rounds of the loaded set (a point with a negative force dropped each) are bounded by the points; those of
// a starting slip's direction by tol::kDirectionRounds (tolerances.hpp).
constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

// The face's unknowns and system: at most 11, on the stack (a solve per evaluation of the rates).
using FaceVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 11, 1>;
using FaceMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 11, 11>;

struct FaceSolution {
  FaceVector x;  // a (3), α (3), c (3), then the sticking point's tangential force (2)
  PointList<double> normals;
  Vec3 acceleration(const Motion& m, const Vec3& r) const {
    return x.segment<3>(0) + Vec3(x.segment<3>(3)).cross(r) + m.omega.cross(m.omega.cross(r));
  }
};

// Newton–Euler's six equations, the flush face's three and, with a sticking point, its two of zero
// tangential acceleration: linear in (a, α, c, f). Points in `loaded` carry N_i = b_i·c; sliding ones take
// F_i = N_i·(−μ·ŝ_i, 1), the sticking one F = (f, N).
std::optional<FaceSolution> solve_face(const ContactBody& body, const Motion& motion,
                                       std::span<const Vec3> arms, double mu,
                                       const PointList<Vec2>& directions, const PointList<char>& loaded,
                                       std::size_t sticking) {
  const std::size_t n = arms.size();
  Vec2 centre = Vec2::Zero();
  int count = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (loaded[i]) centre += arms[i].head<2>(), ++count;
  if (count < 3) return std::nullopt;
  centre /= count;
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), 3);
  double extent = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!loaded[i]) continue;
    const Vec2 d = arms[i].head<2>() - centre;
    B.row(static_cast<Eigen::Index>(i)) << 1, d.x(), d.y();
    extent = std::max(extent, d.norm());
  }
  // Collinear points (an edge) hold no face: the smallest singular value of the scaled columns.
  Eigen::MatrixXd scaled = B;
  scaled.rightCols<2>() /= extent;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled);
  if (!(svd.singularValues()(2) > tol::kCollinearFace * svd.singularValues()(0))) return std::nullopt;
  const bool sticks = sticking != kNone;
  const Eigen::Index size = sticks ? 11 : 9;
  const Vec3& w = motion.omega;
  const double m = body.mass;
  FaceMatrix A = FaceMatrix::Zero(size, size);
  FaceVector rhs = FaceVector::Zero(size);
  // m·a − Σ F_i = −m·g·ẑ and I·α − Σ r_i × F_i = −C·ω − ω × I·ω.
  A.block<3, 3>(0, 0) = m * Mat3::Identity();
  A.block<3, 3>(3, 3) = body.inertia;
  rhs.segment<3>(0) = Vec3(0, 0, -m * body.gravity);
  rhs.segment<3>(3) = -body.damping * w - w.cross(body.inertia * w);
  for (std::size_t i = 0; i < n; ++i) {
    if (!loaded[i]) continue;
    const Vec3 d = i == sticking ? Vec3::UnitZ() : Vec3(-mu * directions[i].x(), -mu * directions[i].y(), 1);
    const Eigen::RowVector3d b = B.row(static_cast<Eigen::Index>(i));
    const Vec3& r = arms[i];
    A.block<3, 3>(0, 6) -= d * b;
    A.block<3, 3>(3, 6) -= r.cross(d) * b;
    // The flush face: Bᵀ·(a_z + (α × r_i)_z + (ω × (ω × r_i))_z) = 0, the normal accelerations being affine
    // over the face.
    A.block<3, 1>(6, 2) += b.transpose();
    A.block<3, 1>(6, 3) += b.transpose() * r.y();
    A.block<3, 1>(6, 4) -= b.transpose() * r.x();
    rhs.segment<3>(6) -= b.transpose() * w.cross(w.cross(r)).z();
  }
  if (sticks) {
    const Vec3& r = arms[sticking];
    const Vec3 centripetal = w.cross(w.cross(r));
    A(0, 9) = A(1, 10) = -1;
    A.block<3, 1>(3, 9) = -r.cross(Vec3::UnitX());
    A.block<3, 1>(3, 10) = -r.cross(Vec3::UnitY());
    // (a + α × r + ω × (ω × r))_x = 0 and _y = 0.
    A(9, 0) = 1, A(9, 4) = r.z(), A(9, 5) = -r.y(), rhs(9) = -centripetal.x();
    A(10, 1) = 1, A(10, 5) = r.x(), A(10, 3) = -r.z(), rhs(10) = -centripetal.y();
  }
  const Eigen::FullPivLU<FaceMatrix> lu(A);
  if (!lu.isInvertible()) return std::nullopt;
  FaceSolution s;
  s.x = lu.solve(rhs);
  if (!s.x.allFinite()) return std::nullopt;
  s.normals.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    s.normals[i] = B.row(static_cast<Eigen::Index>(i)).dot(s.x.segment<3>(6));
  return s;
}

// The face with the point at rest starting to slide: friction −μ·N·ŝ against the slip's acceleration, which
// must then point along ŝ (a_t = β·ŝ, β ≥ 0). Fixed-point rounds from `guess` (each takes the direction of
// the slip's acceleration the last gave) converge for most faces; where they do not (μ above about 1 on a
// lopsided face), the roots of ŝ(θ) × a_t(θ) with ŝ·a_t > 0 are scanned on tol::kDirectionSamples angles and
// bisected, and the one nearest `guess` is taken. `directions[at_rest]` is set to the direction found.
std::optional<FaceSolution> starting_slip(const ContactBody& body, const Motion& motion,
                                          std::span<const Vec3> arms, double mu, PointList<Vec2>& directions,
                                          const PointList<char>& loaded, std::size_t at_rest,
                                          const Vec2& guess) {
  const auto slip_at = [&](const Vec2& s) -> std::optional<std::pair<FaceSolution, Vec2>> {
    directions[at_rest] = s;
    auto face = solve_face(body, motion, arms, mu, directions, loaded, kNone);
    if (!face) return std::nullopt;
    const Vec2 slip = face->acceleration(motion, arms[at_rest]).head<2>();
    return std::pair{std::move(*face), slip};
  };
  const auto holds = [&](const Vec2& s, const Vec2& slip) {
    return !(slip.norm() > tol::kStillSlip * body.gravity) ||  // no slip acceleration: any direction holds
           (slip.dot(s) > 0 &&
            std::abs(s.x() * slip.y() - s.y() * slip.x()) <= tol::kStillSlip * slip.norm());
  };
  Vec2 s = guess.normalized();
  for (int k = 0; k < tol::kDirectionRounds; ++k) {
    auto at = slip_at(s);
    if (!at) return std::nullopt;
    if (holds(s, at->second)) return std::move(at->first);
    s = at->second.normalized();
  }
  const auto unit = [](double theta) { return Vec2(std::cos(theta), std::sin(theta)); };
  const auto cross_at = [&](double theta) {
    const Vec2 u = unit(theta);
    const auto at = slip_at(u);
    if (!at) return static_cast<double>(NAN);
    return u.x() * at->second.y() - u.y() * at->second.x();
  };
  // Every sign change of ŝ × a_t is bisected, and its root kept if the slip's acceleration points along ŝ
  // there (near the stick threshold it does only close to the root, where a_t is small and turns fast with
  // ŝ: the ends of a sample interval need not show it).
  const double step = 2 * std::numbers::pi / tol::kDirectionSamples, start = std::atan2(guess.y(), guess.x());
  double best = NAN, best_distance = INFINITY;
  double h0 = cross_at(start);
  for (int k = 1; k <= tol::kDirectionSamples; ++k) {
    const double a = start + step * (k - 1), b = start + step * k, h1 = cross_at(b);
    if (std::isfinite(h0) && std::isfinite(h1) && (h0 <= 0) != (h1 <= 0)) {
      double lo = a, hi = b;
      for (int i = 0; i < tol::kDirectionBisections; ++i) {
        const double mid = 0.5 * (lo + hi), hm = cross_at(mid);
        ((hm <= 0) == (h0 <= 0) ? lo : hi) = mid;
      }
      const double root = 0.5 * (lo + hi),
                   distance = std::min(root - start, 2 * std::numbers::pi - (root - start));
      const auto at = slip_at(unit(root));
      if (at && holds(unit(root), at->second) && distance < best_distance)
        best = root, best_distance = distance;
    }
    h0 = h1;
  }
  if (!std::isfinite(best)) return std::nullopt;
  auto at = slip_at(unit(best));
  if (!at || !holds(unit(best), at->second)) return std::nullopt;
  return std::move(at->first);
}

}  // namespace

std::optional<ContactForces> sliding_face(const ContactBody& body, const Motion& motion,
                                          std::span<const Vec3> arms, double mu,
                                          std::span<const PointCondition> conditions) {
  const std::size_t n = arms.size();
  if (n < 3) return std::nullopt;
  std::size_t at_rest = kNone;
  PointList<Vec2> directions(n, Vec2::Zero());
  for (std::size_t i = 0; i < n; ++i) {
    directions[i] = conditions[i].direction;
    if (conditions[i].rule == PointRule::sliding) continue;
    if (conditions[i].rule != PointRule::unilateral || at_rest != kNone) return std::nullopt;
    at_rest = i;
  }
  // The loaded points: all, then round by round the one with the most negative force dropped — whatever the
  // point at rest does. For each set the point at rest sticks if its force is in the cone, else it starts to
  // slide against the acceleration of its slip (the direction found by fixed-point rounds), and the whole
  // solution, not only that point's force, is checked for pulling points again (issue 48: a face solved
  // again for a slide gave other points N < 0).
  PointList<char> loaded(n, 1);
  std::optional<FaceSolution> face;
  bool slides = false;
  const auto worst_of = [&](const FaceSolution& f) {
    std::size_t worst = kNone;
    for (std::size_t i = 0; i < n; ++i)
      if (loaded[i] && f.normals[i] < 0 && (worst == kNone || f.normals[i] < f.normals[worst])) worst = i;
    return worst;
  };
  for (std::size_t round = 0;; ++round) {
    if (round + 3 > n) return std::nullopt;
    const bool rests = at_rest != kNone && loaded[at_rest];
    face = solve_face(body, motion, arms, mu, directions, loaded, rests ? at_rest : kNone);
    if (!face) return std::nullopt;
    std::size_t worst = worst_of(*face);
    slides = rests && !(face->x.segment<2>(9).norm() <= mu * face->normals[at_rest]);
    if (slides) {
      // Sticking would take more than the cone holds (or pull): the slip starts, if a direction exists.
      const Vec2 guess = face->x.segment<2>(9).norm() > 0 ? Vec2(-face->x.segment<2>(9)) : Vec2::UnitX();
      PointList<Vec2> trial = directions;
      if (auto sliding = starting_slip(body, motion, arms, mu, trial, loaded, at_rest, guess)) {
        face = std::move(sliding);
        directions = trial;
        worst = worst_of(*face);
      } else if (worst == kNone) {
        return std::nullopt;  // neither sticking nor a start of slip on this set
      } else {
        slides = false;
      }
    }
    if (worst == kNone) break;
    loaded[worst] = 0;
  }
  ContactForces out;
  out.acceleration = face->x.segment<3>(0);
  out.angular_acceleration = face->x.segment<3>(3);
  out.forces.resize(n, Vec3::Zero());
  out.modes.resize(n);
  out.inconsistent.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const double normal = loaded[i] ? face->normals[i] : 0.0;
    const bool sticks = i == at_rest && loaded[i] && !slides;
    out.forces[i] = sticks ? Vec3(face->x(9), face->x(10), normal)
                           : normal * Vec3(-mu * directions[i].x(), -mu * directions[i].y(), 1);
    out.modes[i] = !(normal > 0) ? ContactMode::open : sticks ? ContactMode::stick : ContactMode::slide;
  }
  return out;
}

}  // namespace repose::sim
