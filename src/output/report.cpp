#include "repose/output/report.hpp"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "../model/param_json.hpp"

namespace repose {

namespace {
nlohmann::json vec_json(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
nlohmann::json quat_json(const Quat& q) { return {q.w(), q.x(), q.y(), q.z()}; }
}  // namespace

std::string file_report_json(const MeshReport& r) {
  return nlohmann::json{{"vertices", r.input_vertices},
                        {"triangles", r.input_triangles},
                        {"duplicate_vertices", r.welded_vertices},
                        {"degenerate_triangles", r.degenerate_triangles},
                        {"unused_vertices", r.unused_vertices},
                        {"flipped", r.flipped},
                        {"warnings", r.warnings}}
      .dump();
}

std::string repair_report_json(const RepairReport& r) {
  return nlohmann::json{{"merged_vertices", r.merged_vertices},
                        {"flat_components", r.flat_components},
                        {"input_components", r.input_components},
                        {"kept_components", r.kept_components},
                        {"stitched_edges", r.stitched_edges},
                        {"duplicate_faces", r.duplicate_faces},
                        {"degenerate_faces", r.degenerate_faces},
                        {"non_manifold_vertices", r.non_manifold_vertices},
                        {"flipped_faces", r.flipped_faces},
                        {"holes_filled", r.holes_filled},
                        {"area_added", r.area_added},
                        {"volume_change", r.volume_change},
                        {"notes", r.notes}}
      .dump();
}

std::string settle_summary_json(const Particle& particle, const SettleParams& params, const Quat& initial,
                                const SettleResult& r) {
  nlohmann::json j;
  j["units"] = units_json(unit_names_for_gravity(params.gravity));
  j["particle"] = {{"source", particle.name},
                   {"mass", particle.mass.mass},
                   {"volume", particle.mass.volume},
                   {"characteristic_length", particle.length},
                   {"inertia",
                    {vec_json(particle.mass.inertia.row(0)), vec_json(particle.mass.inertia.row(1)),
                     vec_json(particle.mass.inertia.row(2))}},
                   {"smooth", r.smooth}};
  nlohmann::json& parameters = j["parameters"];
  for (const ParamInfo& info : param_table())
    if (info.uses & in_summary) parameters[info.name] = param_json(info, params);
  parameters["dt"] = r.dt;  // the step the run used: "0: automatic" resolved
  parameters["initial_orientation"] = quat_json(initial);
  j["status"] = to_string(r.status);
  j["time_to_rest"] = r.status == Status::rest ? nlohmann::json(r.time) : nlohmann::json(nullptr);
  j["time"] = r.time;
  j["stable_time"] = r.stable_time >= 0 ? nlohmann::json(r.stable_time) : nlohmann::json(nullptr);
  j["steps"] = r.steps;
  j["max_penetration"] = r.max_penetration;
  nlohmann::json points = nlohmann::json::array();
  for (const Vec3& p : r.contact_points) points.push_back(vec_json(p));
  j["rest"] = {
      {"orientation", quat_json(r.orientation)},
      {"com", vec_json(r.com)},
      {"contact", r.rest == RestKind::none ? "none" : to_string(r.rest)},
      {"contact_points", points},
      {"down_normal_body", vec_json(r.down_normal_body)},
      {"face", r.rest_face},
      // Exact centre-of-mass height for this rest face: the face plane's distance from the centre of mass.
      {"face_com_height",
       r.rest_face >= 0 ? nlohmann::json(particle.hull.faces[r.rest_face].offset) : nlohmann::json(nullptr)}};
  nlohmann::json phases = nlohmann::json::array();
  for (const Phase& p : r.phases)
    phases.push_back({{"contact", to_string(p.contact)}, {"t0", p.t0}, {"t1", p.t1}});
  j["phases"] = phases;
  nlohmann::json impacts = nlohmann::json::array();
  for (const ImpactRecord& i : r.impacts)
    impacts.push_back({{"t", i.t},
                       {"point", vec_json(i.point)},
                       {"points", i.points},
                       {"normal_speed_before", i.normal_speed_before},
                       {"normal_speed_after", i.normal_speed_after},
                       {"tangential_speed_before", i.tangential_speed_before},
                       {"tangential_speed_after", i.tangential_speed_after},
                       {"stick", i.stick},
                       {"energy_before", i.energy_before},
                       {"energy_after", i.energy_after},
                       {"rebound", i.rebound},
                       {"unresolved", i.unresolved}});
  j["impacts"] = impacts;
  j["bounces"] = r.bounces;
  double impact_losses = 0;
  for (const ImpactRecord& i : r.impacts) impact_losses += i.energy_before - i.energy_after;
  // The ledger (finite friction): what friction, the damping moment of the frictional contact phase and the
  // impacts took; with friction infinite the paper's phase's damping is not in it.
  j["energy"] = {{"start", r.energy_start},
                 {"end", r.energy_end},
                 {"friction_work", r.friction_work},
                 {"damping_work", r.damping_work},
                 {"impact_losses", impact_losses}};
  if (const auto& f = r.frictional) {
    // Finite friction: the whole ledger (its terms close ΔE to the integrator's tolerance, "residual") and
    // every fallback counted by kind (friction infinite prints neither, and its output is unchanged).
    nlohmann::json& e = j["energy"];
    e["change"] = r.energy_end - r.energy_start;
    e["normal_work"] = f->normal_work;
    e["stopping_losses"] = f->stopping_losses;
    e["drift_corrections"] = f->drift_corrections;
    e["repositioning"] = f->repositioning;
    e["rest_losses"] = f->rest_losses;
    e["paper_phase_losses"] = f->paper_phase_losses;
    e["frictionless_motion"] = f->frictionless_motion;
    e["residual"] = r.energy_end - r.energy_start + impact_losses + r.friction_work + r.damping_work -
                    f->normal_work + f->stopping_losses + f->drift_corrections - f->repositioning +
                    f->rest_losses + f->paper_phase_losses + f->frictionless_motion;
    j["fallbacks"] = {
        {"handovers_stalled", f->handovers_stalled}, {"handovers_timed_out", f->handovers_timed_out},
        {"bounded_rounds", f->bounded_rounds},       {"pyramid_forces", f->pyramid_forces},
        {"unsolved_forces", f->unsolved_forces},     {"unresolved_forces", f->unresolved_forces}};
    j["captures"] = {{"zeno", f->zeno_captures}, {"painleve", r.painleve}, {"tip_offs", f->tip_offs}};
  }
  j["sliding_distance"] = r.sliding_distance;
  j["painleve"] = r.painleve;
  j["unconverged_steps"] = r.unconverged_steps;
  return j.dump(2) + "\n";
}

std::string time_series_header() {
  return "t,qw,qx,qy,qz,omega_x,omega_y,omega_z,com_x,com_y,com_z,contact,contact_count,kinetic_energy,"
         "potential_energy,sticking,sliding\n";
}

std::string time_series_row(const Sample& s) {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "%.9g,%.12g,%.12g,%.12g,%.12g,%.9g,%.9g,%.9g,%.12g,%.12g,%.12g,%s,%d,%.9g,%.12g,%d,%d\n", s.t,
                s.orientation.w(), s.orientation.x(), s.orientation.y(), s.orientation.z(), s.omega.x(),
                s.omega.y(), s.omega.z(), s.com.x(), s.com.y(), s.com.z(), to_string(s.contact),
                s.contact_count, s.kinetic_energy, s.potential_energy, s.sticking, s.sliding);
  return buf;
}

}  // namespace repose
