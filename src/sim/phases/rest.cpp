// The rest phase's start: the flush rest on a hull face (section 2.4).
#include "rest.hpp"

#include <algorithm>
#include <cmath>

#include "../wall/stability.hpp"

namespace repose::sim {

int face_under_com(const Run& run, const Support& support) {
  const Particle& particle = run.particle;
  const Quat& q = run.q;
  const auto world_vertex = [&](int k) -> Vec3 {
    return support.world + q * (particle.hull.vertices[static_cast<std::size_t>(k)] - support.body);
  };
  const Vec3 down(0, 0, -1);
  int best = -1;
  double best_down = -INFINITY;
  for (std::size_t f = 0; f < particle.hull.faces.size(); ++f) {
    const HullFace& face = particle.hull.faces[f];
    const Vec3 n = q * face.normal;
    if (n.z() >= 0 || -n.z() <= best_down) continue;
    const Vec3 a = world_vertex(face.loop[0]);
    for (std::size_t i = 1; i + 1 < face.loop.size(); ++i) {
      if (ray_hits_triangle(run.com, down, a, world_vertex(face.loop[i]), world_vertex(face.loop[i + 1]))) {
        best = static_cast<int>(f);
        best_down = -n.z();
        break;
      }
    }
  }
  return best;
}

std::optional<RestPose> flush_rest(Run& run, const Support& support) {
  const Particle& particle = run.particle;
  const Quat& q = run.q;
  const Vec3 down(0, 0, -1);
  const int best = face_under_com(run, support);
  if (best < 0 || particle.face_stability_margin[static_cast<std::size_t>(best)] <= 0) return std::nullopt;

  // Rotate the face flush about the support point, then lift or lower it onto the wall exactly.
  const HullFace& face = particle.hull.faces[static_cast<std::size_t>(best)];
  const Quat align = Quat::FromTwoVectors(q * face.normal, down);
  run.q = (align * run.q).normalized();
  const Vec3 pivot = support.world;
  run.com = pivot + align * (run.com - pivot);
  double lowest = INFINITY;
  for (int k : face.loop) lowest = std::min(lowest, (run.com + run.q * particle.hull.vertices[k]).z());
  run.com.z() -= lowest;

  RestPose rest;
  double deepest = 0;
  for (const Vec3& v : particle.hull.vertices) deepest = std::min(deepest, (run.com + run.q * v).z());
  run.record.note_depth(-deepest);
  for (int k : face.loop) rest.points.push_back(run.com + run.q * particle.hull.vertices[k]);
  rest.face = best;
  rest.kind = run.surface.rest_kind(particle.face_is_flat[static_cast<std::size_t>(best)]);
  // Whatever the band looked like on the way down, the particle now rests on a face: a surface contact.
  if (run.surface.has_contact_types()) run.record.set_type(ContactType::surface, run.t);
  if (!run.record.phases.empty()) run.record.phases.back().t1 = run.t;
  return rest;
}

}  // namespace repose::sim
