// The frictional contact phase's impulses (frictional_contact.hpp): impacts (Zeno's captures among them),
// the stopping of points newly at rest and Painlevé's impacts without collision.
#include <algorithm>
#include <cmath>

#include "../body/kinematics.hpp"
#include "../impact/multi_impact.hpp"
#include "frictional_contact.hpp"
#include "impact.hpp"

namespace repose::sim {

// Points approaching the wall strike it (Stronge's E and Coulomb's μ; several at once by the multi-point law
// with every point on the wall). True if any did. The impact is plastic (E = 0) when too slow to leave the
// band again: below the separation speed (a rebound that gravity alone would turn back within the band), or
// a Zeno capture — a rebound E·u that the point's own normal acceleration a_n under the other points' forces
// turns back within the band, (E·u)² ≤ 2·|a_n|·band. Such a rebound would start a cascade of ever smaller
// impacts (a block rocking between two edges of its face, a polyhedron rolling across an edge) that ends, in
// a finite time, with the point on the wall; the plastic impact ends it at once, pushing and in the cone, the
// cascade's energy (below m·|a_n|·band) in the impact's loss.
bool FrictionalContact::resolve_impacts() {
  Run& run = run_;
  // Inline lists: this runs after every step of the phase, and most find no impact.
  PointList<Vec3> arms;
  PointList<int> others;  // the points on the wall not approaching it
  PointList<PointCondition> other_conditions;
  double fastest = 0;
  Vec3 fastest_arm = Vec3::Zero();
  for (std::size_t i = 0; i < active_.size(); ++i) {
    const Vec3 arm = run.q * run.particle.hull.vertices[static_cast<std::size_t>(active_[i])];
    arms.push_back(arm);
    const double approach = -point_velocity(velocity_, omega_, arm).z();
    if (approach > fastest) fastest = approach, fastest_arm = arm;
    if (approach <= run.tol.speed) others.push_back(active_[i]), other_conditions.push_back(conditions_[i]);
  }
  if (fastest <= run.tol.speed) return false;
  // The points leaving the wall from on it (touching, as an approaching point must be to strike) take part:
  // the impact can push them back into it. Struck one at a time, two corners of an edge landing at once
  // traded ever smaller impacts without end (a rod's ends, each rebound driving the other in).
  const Mat3 R = run.q.toRotationMatrix();
  const Vec3 up = R.row(2).transpose();  // a vertex's height needs only this row
  const auto& verts = run.particle.hull.vertices;
  const double touching = tol::kPierceFloor * run.tol.event;
  for (int k : run.near_wall.vertices_below(run.q, run.com.z(), touching, run.tol.event, [&](int k) {
         return !(run.com.z() + up.dot(verts[static_cast<std::size_t>(k)]) > touching);
       })) {
    const Vec3 arm = R * verts[static_cast<std::size_t>(k)];
    if (point_velocity(velocity_, omega_, arm).z() > run.tol.speed) arms.push_back(arm);
  }
  const double elastic = std::max(run.tol.separation_speed, run.params.restitution_threshold);
  double restitution = fastest > elastic ? run.params.restitution : 0.0;
  const double rebound = restitution * fastest;
  if (rebound > 0 && rebound <= tol::kZenoReach * run.tol.separation_speed) {
    const ContactForces f = forces_at({run.com, velocity_, run.q, omega_}, {others.begin(), others.end()},
                                      view(other_conditions));  // the others' forces
    const double a_n = point_acceleration(f.acceleration, f.angular_acceleration, omega_, fastest_arm).z();
    if (a_n < 0 && rebound * rebound <= 2 * -a_n * run.tol.frictional_band) {
      restitution = 0;
      ++run.record.account.zeno_captures;
    }
  }
  const ImpactLaw law{restitution, run.params.friction};
  const Impact::Outcome out =
      Impact(run).resolve({velocity_, omega_}, std::vector<Vec3>(arms.begin(), arms.end()), law, true);
  velocity_ = out.motion.velocity;
  omega_ = out.motion.omega;
  return true;
}

// The least-norm impulses at the points `arms` that bring them to rest: their velocities are u = u0 + W·P
// with W the stacked Delassus matrix (blocks K_ij); an edge's two corners leave the rotation about it free.
Eigen::VectorXd FrictionalContact::stopping_impulses(const std::vector<Vec3>& arms, bool along) const {
  const Mat3 R = run_.q.toRotationMatrix();
  const Mat3 inverse_inertia = world_inverse_inertia(R, run_.body.inertia);
  const double m = run_.body.mass;
  const std::size_t n = arms.size();
  Eigen::MatrixXd W(3 * n, 3 * n);
  Eigen::VectorXd u0(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    u0.segment<3>(3 * i) = point_velocity(velocity_, omega_, arms[i]);
    for (std::size_t j = 0; j < n; ++j)
      W.block<3, 3>(3 * i, 3 * j) = delassus_block(m, inverse_inertia, arms[i], arms[j]);
  }
  if (along) return W.completeOrthogonalDecomposition().solve(-u0);
  // The normal components only: W's normal rows and columns.
  Eigen::MatrixXd G(n, n);
  Eigen::VectorXd un(n);
  for (std::size_t i = 0; i < n; ++i) {
    un(static_cast<Eigen::Index>(i)) = u0(3 * static_cast<Eigen::Index>(i) + 2);
    for (std::size_t j = 0; j < n; ++j)
      G(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
          W(3 * static_cast<Eigen::Index>(i) + 2, 3 * static_cast<Eigen::Index>(j) + 2);
  }
  const Eigen::VectorXd Pn = G.completeOrthogonalDecomposition().solve(-un);
  Eigen::VectorXd P = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i)
    P(3 * static_cast<Eigen::Index>(i) + 2) = Pn(static_cast<Eigen::Index>(i));
  return P;
}

// The stopping impulses of stopping_impulses(arms, true) with the points that the joint solution would pull
// left free, one at a time, the most pulled first (at most one round a point); zero at the points left free.
Eigen::VectorXd FrictionalContact::stopping_impulses_pushing(const std::vector<Vec3>& arms) const {
  const std::size_t n = arms.size();
  std::vector<std::size_t> kept(n);
  for (std::size_t i = 0; i < n; ++i) kept[i] = i;
  Eigen::VectorXd P = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(n));
  for (std::size_t round = 0; round < n && !kept.empty(); ++round) {
    std::vector<Vec3> set;
    for (std::size_t i : kept) set.push_back(arms[i]);
    const Eigen::VectorXd Q = stopping_impulses(set, true);
    std::size_t worst = kept.size();
    for (std::size_t j = 0; j < kept.size(); ++j)
      if (Q(3 * static_cast<Eigen::Index>(j) + 2) < 0 &&
          (worst == kept.size() ||
           Q(3 * static_cast<Eigen::Index>(j) + 2) < Q(3 * static_cast<Eigen::Index>(worst) + 2)))
        worst = j;
    if (worst == kept.size()) {
      for (std::size_t j = 0; j < kept.size(); ++j)
        P.segment<3>(3 * static_cast<Eigen::Index>(kept[j])) = Q.segment<3>(3 * static_cast<Eigen::Index>(j));
      break;
    }
    kept.erase(kept.begin() + static_cast<std::ptrdiff_t>(worst));
  }
  return P;
}

// Points at rest on the wall keep a residual velocity (below 2·slip_speed along the wall, below speed across
// it). Where it drives a point newly at rest (a slide that stopped, a landing) into the wall, the point is
// stopped by the plastic impact law with Coulomb's friction (collide_points, E = 0: no impulse pulls, every
// one in its cone; issue 48), in stopping_losses. What is left at every point at rest is below the speeds
// by which the model calls it at rest: undone by the least-norm velocity change that brings those points to
// rest — a projection onto the model's own state, not an impulse of the wall — along the wall only where
// there is friction (μ > 0), its kinetic energy in the ledger (drift_corrections). Without it the rule of a
// point at rest (its acceleration, not its residual slip, decides its friction) let friction do positive
// work on that slip.
// The points at rest now (hull vertices), and whether each was at rest in the segment before too.
std::vector<std::pair<Vec3, bool>> FrictionalContact::resting_points() const {
  std::vector<std::pair<Vec3, bool>> out;
  for (std::size_t i = 0; i < active_.size(); ++i) {
    if (conditions_[i].rule != PointRule::unilateral) continue;
    const int k = active_[i];
    const bool held = std::find(at_rest_before_.begin(), at_rest_before_.end(), k) != at_rest_before_.end();
    out.emplace_back(run_.q * run_.particle.hull.vertices[static_cast<std::size_t>(k)], held);
  }
  return out;
}

bool FrictionalContact::stop_landed_points() {
  std::vector<Vec3> landed;
  bool approaching = false;
  for (const auto& [arm, held] : resting_points()) {
    if (held) continue;
    landed.push_back(arm);
    approaching = approaching || point_velocity(velocity_, omega_, arm).z() < 0;
  }
  if (!approaching) return false;
  const double before = kinetic_energy();
  const Mat3 R = run_.q.toRotationMatrix();
  const MultiImpactOutcome out = collide_points(run_.body.mass, world_inertia(R, run_.body.inertia), landed,
                                                {velocity_, omega_}, {0.0, run_.params.friction});
  run_.record.account.unresolved_forces += !out.converged;
  velocity_ = out.after.velocity;
  omega_ = out.after.omega;
  run_.record.account.stopping_losses += before - kinetic_energy();
  return true;
}

void FrictionalContact::undo_drift() {
  std::vector<Vec3> held;
  for (const auto& [arm, was_held] : resting_points()) held.push_back(arm);
  at_rest_before_.clear();
  sliding_before_.clear();
  for (std::size_t i = 0; i < active_.size(); ++i)
    (conditions_[i].rule == PointRule::unilateral ? at_rest_before_ : sliding_before_).push_back(active_[i]);
  if (!held.empty()) project_to_rest(held, run_.params.friction > 0);
}

void FrictionalContact::project_to_rest(const std::vector<Vec3>& arms, bool along) {
  const Mat3 R = run_.q.toRotationMatrix();
  const Mat3 inverse_inertia = world_inverse_inertia(R, run_.body.inertia);
  const double before = kinetic_energy();
  const Eigen::VectorXd P = stopping_impulses(arms, along);
  for (std::size_t i = 0; i < arms.size(); ++i) {
    const Vec3 p = P.segment<3>(3 * static_cast<Eigen::Index>(i));
    velocity_ += p / run_.body.mass;
    omega_ += inverse_inertia * arms[i].cross(p);
  }
  run_.record.account.drift_corrections += before - kinetic_energy();
}

// A point leaving the wall so slowly that the normal acceleration the other points give it turns it back
// before it rises by the event tolerance (u_n² ≤ 2·|a_n|·event, 1e-12·L) makes a hop no event can resolve:
// its return would be found at once, again and again. It is held on the wall: its normal velocity, and the
// other points', undone by the least-norm change of velocity (a projection of motion below the engine's
// resolution, like undo_drift's; its kinetic energy in drift_corrections), counted as a Zeno capture. A
// slow leaving point that rises above the event tolerance hops, and its return is an impact
// (resolve_impacts).
bool FrictionalContact::hold_unresolved_hops() {
  Run& run = run_;
  const auto& verts = run.particle.hull.vertices;
  std::vector<Vec3> arms;
  for (int k : leaving_slowly_) {
    const Vec3 r = run.q * verts[static_cast<std::size_t>(k)], u = point_velocity(velocity_, omega_, r);
    const double a = point_acceleration(forces_.acceleration, forces_.angular_acceleration, omega_, r).z();
    if (a < 0 && u.z() * u.z() <= 2 * -a * run.tol.event) arms.push_back(r);
  }
  if (arms.empty()) return false;
  ++run.record.account.zeno_captures;
  for (int k : active_) arms.push_back(run.q * verts[static_cast<std::size_t>(k)]);
  project_to_rest(arms, false);
  return true;
}

// Painlevé's inconsistent case at sliding points (no normal force holds them on the wall): an impact without
// collision (Génot & Brogliato 1999), the dynamic jam ending in sticking — the impulses at those points, all
// at once, that stop them (the least-norm ones: an edge's two corners leave the rotation about it free),
// each kept in its friction cone: a point whose normal impulse would pull is left free and the others are
// stopped again without it (the most pulled first, at most once each: a pulling impulse merely dropped from
// the joint solution left the others' impulses solved for a stop that no longer happened, a kick that
// started a hold / jam / impact cycle), and a tangential impulse beyond the cone is projected onto it.
// Counted, and recorded as an impact. True if any point met it.
bool FrictionalContact::resolve_painleve() {
  Run& run = run_;
  std::vector<Vec3> arms;
  for (std::size_t i = 0; i < active_.size(); ++i)
    if (i < forces_.inconsistent.size() && forces_.inconsistent[i])
      arms.push_back(run.q * run.particle.hull.vertices[static_cast<std::size_t>(active_[i])]);
  if (arms.empty()) return false;
  run.record.painleve += static_cast<int>(arms.size());
  const Mat3 R = run.q.toRotationMatrix();
  const Mat3 inertia = world_inertia(R, run.body.inertia);
  const Mat3 inverse_inertia = inertia.inverse();
  const double m = run.body.mass;
  const std::size_t n = arms.size();
  const Vec3 before = point_velocity(velocity_, omega_, arms[0]);  // the record's speeds before
  const Eigen::VectorXd P = stopping_impulses_pushing(arms);
  ImpactRecord record;
  record.t = run.t;
  record.points = static_cast<int>(n);
  record.stick = true;
  record.energy_before = sim::kinetic_energy(m, inertia, {velocity_, omega_}) + run.potential_energy();
  std::vector<Vec3> impulses(n, Vec3::Zero());
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 p = P.segment<3>(3 * i);
    if (!(p.z() > 0)) continue;
    const double cone = run.params.friction * p.z(), t = p.head<2>().norm();
    if (t > cone) p.head<2>() *= cone / t;
    impulses[i] = p;
  }
  // Dropping and projecting can leave impulses that add kinetic energy: scaled to their energy minimum.
  const double scale = energy_minimising_scale(m, inertia, {velocity_, omega_}, arms, impulses);
  const Vec3 velocity_before = velocity_;
  const Motion jammed = apply_impulses(m, inverse_inertia, {velocity_, omega_}, arms, impulses, scale);
  velocity_ = jammed.velocity;
  omega_ = jammed.omega;
  Vec3 centre = Vec3::Zero();
  double total = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double pn = (scale * impulses[i]).z();
    centre += pn * arms[i];
    total += pn;
  }
  const Vec3 at = total > 0 ? Vec3(centre / total) : arms[0];
  const Vec3 after = point_velocity(velocity_, omega_, at);
  record.point = run.com + at;
  record.normal_speed_before = before.z();
  record.tangential_speed_before = before.head<2>().norm();
  record.normal_speed_after = after.z();
  record.tangential_speed_after = after.head<2>().norm();
  record.energy_after = sim::kinetic_energy(m, inertia, {velocity_, omega_}) + run.potential_energy();
  record.impulse = m * (velocity_ - velocity_before);
  run.record.impacts.push_back(record);
  return true;
}

}  // namespace repose::sim
