// The design target (target.hpp): its JSON forms, checked, and its outcomes' hull faces.
#include "repose/design/target.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "repose/error.hpp"

namespace repose {

namespace {

// Tolerances of a target as read: probabilities sum to 1 within kSumTolerance; two normals closer than
// kDistinctAngle (rad) are one outcome given twice.
constexpr double kSumTolerance = 1e-6;
constexpr double kDistinctAngle = 1e-6;

[[noreturn]] void fail(const std::string& source, const std::string& problem) {
  throw Error("design target " + source + ": " + problem);
}

Vec3 read_normal(const nlohmann::json& j, const std::string& source, std::size_t index) {
  const std::string where = "outcome " + std::to_string(index + 1);
  if (!j.is_array() || j.size() != 3 ||
      !std::all_of(j.begin(), j.end(), [](auto& x) { return x.is_number(); }))
    fail(source, where + ": the normal is not three numbers");
  const Vec3 n(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
  if (!n.allFinite() || !(n.norm() > 0)) fail(source, where + ": the normal is zero or not finite");
  return n.normalized();
}

double read_probability(const nlohmann::json& j, const std::string& source, std::size_t index) {
  if (!j.is_number())
    fail(source, "outcome " + std::to_string(index + 1) + ": the probability is not a number");
  const double p = j.get<double>();
  if (!std::isfinite(p) || p < 0 || p > 1)
    fail(source,
         "outcome " + std::to_string(index + 1) + ": probability " + std::to_string(p) + " is not in [0, 1]");
  return p;
}

double degrees(double rad) { return rad * 180 / std::numbers::pi; }

}  // namespace

DesignTarget parse_design_target(std::string_view json_text, const std::string& source) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(json_text);
  } catch (const nlohmann::json::parse_error& e) {
    // nlohmann's message ends with its own detail; the byte offset is what a user needs.
    fail(source, "not valid JSON (at byte " + std::to_string(e.byte) + ")");
  }
  DesignTarget target;
  target.source = source;
  if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i) {
      if (!j[i].is_array() || j[i].size() != 2)
        fail(source, "outcome " + std::to_string(i + 1) + ": a pair [[nx, ny, nz], p] was expected");
      target.outcomes.push_back({read_normal(j[i][0], source, i), read_probability(j[i][1], source, i), {}});
    }
  } else if (j.is_object() && ((j.contains("outcomes") && j["outcomes"].is_array()) ||
                               (j.contains("pairs") && j["pairs"].is_array()))) {
    // "pairs" is convex_dice's own file (its examples' final_normal_probs.json), read as it is.
    const auto& list = j.contains("outcomes") ? j["outcomes"] : j["pairs"];
    for (std::size_t i = 0; i < list.size(); ++i) {
      if (!list[i].is_object() || !list[i].contains("normal") || !list[i].contains("probability"))
        fail(source, "outcome " + std::to_string(i + 1) + ": \"normal\" and \"probability\" are needed");
      target.outcomes.push_back({read_normal(list[i]["normal"], source, i),
                                 read_probability(list[i]["probability"], source, i),
                                 {}});
    }
  } else if (j.is_object() && j.contains("fair") && j["fair"].is_array()) {
    const auto& list = j["fair"];
    for (std::size_t i = 0; i < list.size(); ++i)
      target.outcomes.push_back({read_normal(list[i], source, i), 0, {}});
    for (auto& o : target.outcomes) o.probability = 1.0 / static_cast<double>(target.outcomes.size());
  } else {
    fail(source,
         "expected [[normal, p], ...], {\"outcomes\": [...]}, {\"pairs\": [...]} or {\"fair\": [normals]}");
  }
  if (target.outcomes.empty()) fail(source, "no outcomes");
  double sum = 0;
  for (const auto& o : target.outcomes) sum += o.probability;
  if (std::abs(sum - 1) > kSumTolerance) {
    std::ostringstream s;
    s << "the probabilities sum to " << sum << ", not 1";
    fail(source, s.str());
  }
  for (std::size_t a = 0; a < target.outcomes.size(); ++a)
    for (std::size_t b = a + 1; b < target.outcomes.size(); ++b) {
      const Vec3& na = target.outcomes[a].normal;
      const Vec3& nb = target.outcomes[b].normal;
      if (std::atan2(na.cross(nb).norm(), na.dot(nb)) < kDistinctAngle)
        fail(source,
             "outcomes " + std::to_string(a + 1) + " and " + std::to_string(b + 1) + " have the same normal");
    }
  return target;
}

void assign_outcome_faces(DesignTarget& target, const ConvexHull& hull, double max_angle,
                          const std::string& angle_option) {
  for (auto& o : target.outcomes) o.faces.clear();
  target.unassigned_faces.clear();
  // The nearest face of each outcome, for the error of an outcome with none.
  std::vector<double> nearest(target.outcomes.size(), INFINITY);
  for (std::size_t f = 0; f < hull.faces.size(); ++f) {
    const Vec3& n = hull.faces[f].normal;
    std::size_t best = 0;
    double best_angle = INFINITY;
    for (std::size_t k = 0; k < target.outcomes.size(); ++k) {
      const Vec3& m = target.outcomes[k].normal;
      const double angle = std::atan2(n.cross(m).norm(), n.dot(m));
      nearest[k] = std::min(nearest[k], angle);
      if (angle < best_angle) best_angle = angle, best = k;
    }
    if (best_angle <= max_angle)
      target.outcomes[best].faces.push_back(static_cast<int>(f));
    else
      target.unassigned_faces.push_back(static_cast<int>(f));
  }
  for (std::size_t k = 0; k < target.outcomes.size(); ++k)
    if (target.outcomes[k].faces.empty()) {
      const Vec3& m = target.outcomes[k].normal;
      std::ostringstream s;
      s << "design target " << (target.source.empty() ? std::string("(unnamed)") : target.source)
        << ": outcome " << k + 1 << "'s normal (" << m.x() << ", " << m.y() << ", " << m.z()
        << ") is no outcome of this hull: its nearest face is " << degrees(nearest[k])
        << " degrees away (at most " << degrees(max_angle) << ": " << angle_option << ")";
      throw Error(s.str());
    }
}

std::vector<double> outcome_probabilities(const DesignTarget& target,
                                          const std::vector<double>& face_probability) {
  std::vector<double> out;
  for (const auto& o : target.outcomes) {
    double p = 0;
    for (int f : o.faces) p += face_probability.at(static_cast<std::size_t>(f));
    out.push_back(p);
  }
  double rest = 0;
  for (int f : target.unassigned_faces) rest += face_probability.at(static_cast<std::size_t>(f));
  out.push_back(rest);
  return out;
}

}  // namespace repose
