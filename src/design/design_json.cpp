// design_json (design_json.hpp).
#include "repose/design/design_json.hpp"

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

std::string design_json(const std::string& source, const DesignTarget& target, const DesignOptions& o,
                        const DesignResult& r) {
  nlohmann::json j;
  j["source"] = source;
  j["target_file"] = target.source;
  j["options"] = {{"vary", to_string(o.freedom)},
                  {"mass", o.mass == MassModel::fixed ? "fixed" : "follows"},
                  {"outcome_angle_degrees", o.outcome_angle * 180 / std::numbers::pi},
                  {"com_margin", o.com_margin},
                  {"max_move", o.max_vertex_move},
                  {"max_step", o.max_step},
                  {"min_edge", o.min_edge},
                  {"min_face", o.min_face_area},
                  {"smoothing", o.smoothing},
                  {"tolerance", o.tolerance},
                  {"iterations", o.max_iterations}};
  nlohmann::json outcomes = nlohmann::json::array();
  for (std::size_t k = 0; k < target.outcomes.size(); ++k)
    outcomes.push_back({{"normal", vec(target.outcomes[k].normal)},
                        {"target", r.target[k]},
                        {"start", r.start[k]},
                        {"achieved", r.achieved[k]}});
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
                       {"trials", s.trials},
                       {"rejected",
                        {{"rose", s.rose},
                         {"unprintable", s.unprintable},
                         {"com_outside", s.com_outside},
                         {"degenerate", s.degenerate}}}});
  j["history"] = history;
  return j.dump(2);
}

}  // namespace repose
