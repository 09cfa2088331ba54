// design_json (design_json.hpp).
#include "repose/design/design_json.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

namespace repose {

namespace {

nlohmann::json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

std::string to_string(const DesignFreedom& freedom) {
  std::string out = freedom.shape == ShapeFreedom::vertices ? "vertices"
                    : freedom.shape == ShapeFreedom::faces  ? "faces"
                                                            : "";
  if (freedom.center_of_mass) out += out.empty() ? "center-of-mass" : "+center-of-mass";
  return out;
}

namespace {

nlohmann::json design_object(const std::string& source, const DesignTarget& target, const DesignOptions& o,
                             const DesignResult& r) {
  nlohmann::json j;
  j["source"] = source;
  j["target_file"] = target.source;
  j["options"] = {{"vary", to_string(o.freedom)},
                  {"mass", o.mass == MassModel::fixed ? "fixed" : "follows"},
                  {"outcome_angle_degrees", o.outcome_angle * 180 / std::numbers::pi},
                  {"outcome_normals", o.follow_outcome_normals ? "follow" : "fixed"},
                  {"com_margin", o.com_margin},
                  {"max_move", o.max_vertex_move},
                  {"max_step", o.max_step},
                  {"min_edge", o.min_edge},
                  {"min_face", o.min_face_area},
                  {"min_margin", o.min_margin},
                  {"smoothing", o.smoothing},
                  {"keep_faces_flat", o.keep_faces_flat},
                  {"tolerance", o.tolerance},
                  {"iterations", o.max_iterations}};
  nlohmann::json outcomes = nlohmann::json::array();
  for (std::size_t k = 0; k < target.outcomes.size(); ++k) {
    outcomes.push_back({{"normal", vec(target.outcomes[k].normal)},
                        {"target", r.target[k]},
                        {"start", r.start[k]},
                        {"achieved", r.achieved[k]},
                        {"margin", r.outcome_margin[k]}});
    // Where the outcome's normal followed its face to (its faces at the design are those nearest it).
    if (o.follow_outcome_normals) outcomes.back()["design_normal"] = vec(r.outcome_normals[k]);
  }
  j["outcomes"] = outcomes;
  j["unassigned"] = {{"target", 0.0}, {"start", r.start.back()}, {"achieved", r.achieved.back()}};
  j["stop"] = r.stop;
  j["reached"] = r.reached();
  j["max_error"] = r.max_error();
  j["center_of_mass"] = vec(r.center_of_mass);
  j["centroid"] = vec(r.centroid);
  // Where the centre of mass sits relative to a uniform part's: what an insert or cavity must move it by.
  j["center_of_mass_offset"] = vec(Vec3(r.center_of_mass - r.centroid));
  j["characteristic_length"] = r.length;
  j["hull"] = {{"vertices", r.vertices.size()}, {"triangles", r.mesh.triangles.size()}};
  nlohmann::json history = nlohmann::json::array();
  for (const DesignStep& s : r.history)
    history.push_back({{"objective", s.objective},
                       {"max_error", s.max_error},
                       {"step", s.step},
                       {"stable_faces", s.stable_faces},
                       {"accepted", s.accepted},
                       {"structure_changed", s.structure_changed},
                       {"outcomes_reassigned", s.outcomes_reassigned},
                       {"normals_kept", s.normals_kept},
                       {"trials", s.trials},
                       {"rejected",
                        {{"rose", s.rose},
                         {"unprintable", s.unprintable},
                         {"com_outside", s.com_outside},
                         {"degenerate", s.degenerate}}}});
  j["history"] = history;
  return j;
}

nlohmann::json tossed_object(const TossedOutcomes& t) {
  nlohmann::json j;
  j["drops"] = {t.drops.begin, t.drops.end};
  j["counts"] = t.counts;
  j["probability"] = t.probability;
  nlohmann::json ci = nlohmann::json::array();
  for (const auto& c : t.ci95) ci.push_back({c[0], c[1]});
  j["ci95"] = ci;
  j["max_error"] = t.max_error;
  j["chi_square"] = std::isfinite(t.chi_square) ? nlohmann::json(t.chi_square) : nlohmann::json("inf");
  j["degrees_of_freedom"] = t.dof;
  j["p_value"] = t.p_value;
  j["all_within_ci95"] = t.all_within_ci95;
  j["all_within_simultaneous_ci95"] = t.all_within_simultaneous;
  if (t.fit_drops > 0) {
    j["fit_drops"] = t.fit_drops;
    j["all_within_fit_and_check"] = t.all_within_fit_and_check;
    j["all_within_fit_and_check_simultaneous"] = t.all_within_fit_and_check_simultaneous;
  }
  return j;
}

}  // namespace

std::string design_json(const std::string& source, const DesignTarget& target, const DesignOptions& o,
                        const DesignResult& r) {
  nlohmann::json j = design_object(source, target, o, r);
  j["model"] = "quasi-static";
  return j.dump(2);
}

std::string toss_design_json(const std::string& source, const DesignTarget& target,
                             const TossDesignOptions& o, const TossDesignResult& r) {
  // The design's own keys are the quasi-static ones of its shape; "tossed" holds what it was designed for.
  nlohmann::json j = design_object(source, target, o.shape, r.design);
  j["model"] = "tossed";
  j["quasi_static_design"] = design_object(source, target, o.shape, r.quasi_static_design);
  j["quasi_static_design"].erase("source");
  j["quasi_static_design"].erase("target_file");
  j["quasi_static_design"].erase("options");
  const StudySettings& s = o.model.settings;
  nlohmann::json tossed;
  tossed["toss"] = {
      {"seed", s.seed},
      {"drops", o.model.drops},
      {"check_drops", o.model.check_drops},
      {"gravity", s.params.gravity},
      {"drop_height", s.params.drop_height},
      {"velocity_max", s.toss.velocity_max},
      {"spin_max", s.toss.spin_max},
      {"restitution", s.params.restitution},
      {"friction",
       std::isfinite(s.params.friction) ? nlohmann::json(s.params.friction) : nlohmann::json("inf")},
      {"restitution_threshold", s.params.restitution_threshold},
      {"damping_ratio", s.damping_given ? nlohmann::json(nullptr) : nlohmann::json(s.damping_ratio)},
      {"damping", s.damping_given ? nlohmann::json(s.params.damping) : nlohmann::json(nullptr)}};
  tossed["stop"] = r.stop;
  tossed["reached"] = r.reached();
  tossed["settles"] = r.settles;
  tossed["check"] = tossed_object(r.check);
  tossed["check_quasi_static_design"] = tossed_object(r.check_quasi_static);
  nlohmann::json history = nlohmann::json::array();
  for (const TossDesignStep& step : r.history)
    history.push_back({{"kind", step.kind},
                       {"surrogate_target", step.surrogate},
                       {"quasi_static", step.quasi_static},
                       {"tossed", tossed_object(step.tossed)},
                       {"objective", step.objective},
                       {"inner_iterations", step.inner_iterations},
                       {"inner_stop", step.inner_stop},
                       {"inner_restarted", step.inner_restarted},
                       {"accepted", step.accepted},
                       {"jacobian_reset", step.jacobian_reset}});
  tossed["history"] = history;
  j["tossed"] = tossed;
  return j.dump(2);
}

}  // namespace repose
