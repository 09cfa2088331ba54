// design_report.hpp.
#include "repose/design/design_report.hpp"

#include "repose/output/html.hpp"

namespace repose {

Particle design_particle(const DesignResult& design, const std::string& name) {
  MeshOptions options;
  options.inertia = InertiaModel::convex;
  options.center_of_mass = design.center_of_mass;
  return make_particle(design.mesh, name, 1.0, options);
}

std::string design_report_html(const std::string& title, const DesignTarget& target,
                               const DesignOptions& options, const DesignResult& design,
                               const std::string& design_json) {
  const Particle body = design_particle(design, title);
  DesignTarget assigned = target;
  // The outcomes as the design assigns them (their normals followed the faces, or the target's).
  for (std::size_t o = 0; o < assigned.outcomes.size() && o < design.outcome_normals.size(); ++o)
    assigned.outcomes[o].normal = design.outcome_normals[o];
  assign_outcome_faces(assigned, body.hull, options.outcome_angle, "--outcome-angle");
  std::vector<int> face_outcome(body.hull.faces.size(), -1);
  for (std::size_t o = 0; o < assigned.outcomes.size(); ++o)
    for (const int f : assigned.outcomes[o].faces)
      face_outcome[static_cast<std::size_t>(f)] = static_cast<int>(o);
  return design_report_page(title, body, face_outcome, design_json);
}

}  // namespace repose
