#include "study_settings.hpp"

#include <cmath>

#include "../model/param_json.hpp"
#include "repose/error.hpp"
#include "repose/model/param_table.hpp"

namespace repose {

namespace {

using nlohmann::json;

const char* study_key(const ParamInfo& info) { return info.study_key ? info.study_key : info.name; }

// What files written before a parameter existed were computed with: the defaults (no rebound, no slip),
// but the paper's integrator, which came before the adaptive one.
SettleParams before_the_field() {
  SettleParams p;
  p.integrator = Integrator::paper;
  return p;
}

// An integer, checked first: nlohmann converts a floating-point value with a plain cast, undefined behaviour
// when it does not fit.
template <class Int>
Int whole_number(const json& v, const std::string& name) {
  if (!v.is_number_integer()) throw Error(name + ": malformed poses result file (expected an integer)");
  return v.get<Int>();
}

// One parameter from `v` (what settings_json wrote): null is infinity where that is valid.
void read_param(const json& v, const ParamInfo& info, SettleParams& p, const std::string& name) {
  std::visit(Overloaded{[&](double SettleParams::*m) {
                          p.*m = v.is_null() && info.range.allows_infinity() ? INFINITY : v.get<double>();
                        },
                        [&](long SettleParams::*m) { p.*m = whole_number<long>(v, name); },
                        [&](int SettleParams::*m) { p.*m = whole_number<int>(v, name); },
                        [&](Vec3 SettleParams::*m) {
                          p.*m = Vec3(v.at(0).get<double>(), v.at(1).get<double>(), v.at(2).get<double>());
                        },
                        [&](const ParamChoice& c) { c.set(p, v.get<std::string>()); }},
             info.member);
}

}  // namespace

json settings_json(const PosesStudy& s) {
  json j;
  for (const ParamInfo& info : param_table())
    if (info.uses & in_study) j[study_key(info)] = param_json(info, s.params);
  j["velocity_max"] = s.toss.velocity_max;
  j["spin_max"] = s.toss.spin_max;
  j["decide_early"] = s.decide_early;
  j["persistence"] = s.catalog.persistence;
  return j;
}

void read_settings(const json& set, PosesStudy& s, const std::string& name) {
  static const SettleParams before = before_the_field();
  for (const ParamInfo& info : param_table()) {
    if (!(info.uses & in_study)) continue;
    const char* key = study_key(info);
    if ((info.uses & study_optional) && !set.contains(key))
      copy_param(info, before, s.params);
    else
      read_param(set.at(key), info, s.params, name);  // missing: nlohmann's out_of_range
  }
  // Files written before tosses existed: drops from rest.
  s.toss.velocity_max = set.value("velocity_max", 0.0);
  s.toss.spin_max = set.value("spin_max", 0.0);
  s.decide_early = set.at("decide_early").get<bool>();
  s.catalog.persistence = set.at("persistence").get<double>();
}

}  // namespace repose
