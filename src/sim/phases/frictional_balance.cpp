// The frictional contact phase's balances (frictional_contact.hpp): a still body that is not resting on a
// face is turned by the paper's rule for an edge balance until gravity tips it, off an unstable face or onto
// the face under its centre of mass.
#include <algorithm>
#include <cmath>

#include "../wall/balance.hpp"
#include "frictional_contact.hpp"
#include "rest.hpp"

namespace repose::sim {

// A still body whose face under the centre of mass is unstable by the paper's test balances on the face's
// boundary: it is turned about the boundary edge nearest the centre of mass (on the wall) until the centre of
// mass is balance_offset beyond it, at rest, from where gravity tips it off (the rule the paper's phase
// applies to an edge balance, wall/balance.hpp). True if it was turned.
bool FrictionalContact::tip_off_balance(const Support& support) {
  Run& run = run_;
  const int f = face_under_com(run, support);
  if (f < 0) return false;
  const HullFace& face = run.particle.hull.faces[static_cast<std::size_t>(f)];
  std::vector<Vec3> loop;
  Vec2 centre = Vec2::Zero();
  for (int k : face.loop) {
    loop.push_back(run.com + run.q * run.particle.hull.vertices[static_cast<std::size_t>(k)]);
    centre += loop.back().head<2>() / static_cast<double>(face.loop.size());
  }
  // The edge the centre of mass is farthest beyond (or least inside), its outward normal in the wall's plane.
  const Vec2 g = run.com.head<2>();
  double lean = -INFINITY;
  Vec3 pivot = Vec3::Zero();
  Vec2 outward = Vec2::Zero();
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec2 a = loop[i].head<2>(), b = loop[(i + 1) % loop.size()].head<2>();
    Vec2 n(b.y() - a.y(), a.x() - b.x());
    if (!(n.norm() > 0)) continue;
    n.normalize();
    if (n.dot(centre - a) > 0) n = -n;
    if ((g - a).dot(n) > lean) lean = (g - a).dot(n), pivot = loop[i], outward = n;
  }
  if (!std::isfinite(lean)) return false;
  turn_past_line(pivot, outward);
  return true;
}

bool FrictionalContact::face_on_wall(int face) const {
  for (int k : run_.particle.hull.faces[static_cast<std::size_t>(face)].loop)
    if (run_.com.z() + (run_.q * run_.particle.hull.vertices[static_cast<std::size_t>(k)]).z() >
        run_.tol.frictional_band)
      return false;
  return true;
}

// A still body on the points `band` (hull vertices within the band), its centre of mass over `face` whose
// points are not all on the wall: it is turned about the line through the two band points farthest apart
// until the centre of mass is balance_offset beyond that line on the face's side. True if it was turned.
bool FrictionalContact::tip_onto_face(const std::vector<int>& band, int face) {
  Run& run = run_;
  const auto world = [&](int k) -> Vec3 {
    return run.com + run.q * run.particle.hull.vertices[static_cast<std::size_t>(k)];
  };
  Vec3 a = world(band[0]), b = a;
  for (std::size_t i = 0; i < band.size(); ++i)
    for (std::size_t j = i + 1; j < band.size(); ++j)
      if ((world(band[j]) - world(band[i])).head<2>().norm() > (b - a).head<2>().norm())
        a = world(band[i]), b = world(band[j]);
  Vec2 outward(b.y() - a.y(), a.x() - b.x());
  if (!(outward.norm() > 0)) return false;
  outward.normalize();
  Vec2 centre = Vec2::Zero();
  const auto& loop = run.particle.hull.faces[static_cast<std::size_t>(face)].loop;
  for (int k : loop) centre += world(k).head<2>() / static_cast<double>(loop.size());
  if (outward.dot(centre - a.head<2>()) < 0) outward = -outward;
  turn_past_line(a, outward);
  return true;
}

// Turns the body at rest about the horizontal line through `pivot` normal to `outward` (a unit vector in the
// wall's plane) until its centre of mass is balance_offset beyond the line along `outward` (the tip-off rule,
// wall/balance.hpp: the line's direction has `outward` to its left).
void FrictionalContact::turn_past_line(const Vec3& pivot, const Vec2& outward) {
  Run& run = run_;
  const BalanceTurn tip =
      tip_off_turn(run.particle.hull.vertices, run.q, run.com, pivot, Vec2(outward.y(), -outward.x()), 1.0,
                   run.tol.balance_offset, run.tol.touch);
  run.record.account.rest_losses += kinetic_energy();
  const double height_before = run.com.z();
  run.q = (tip.turn * run.q).normalized();
  run.com = pivot + tip.turn * (run.com - pivot);
  run.record.account.repositioning += run.body.mass * run.params.gravity * (run.com.z() - height_before);
  velocity_ = omega_ = Vec3::Zero();
}

}  // namespace repose::sim
