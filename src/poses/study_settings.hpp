// The "settings" object of a poses result file: written and read back in one place, so that the field names
// and the defaults of files that predate a field cannot drift apart. (Internal to src/poses.)
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "repose/poses/study.hpp"

namespace repose {

/// The study's settings (physics parameters, toss distribution, early decision, persistence) as JSON.
nlohmann::json settings_json(const PosesStudy& study);

/// Reads what settings_json wrote into `study` (files written before a field existed get the value that
/// was then implied). Throws repose::Error naming `name` for an unknown smooth mode or integrator or a
/// non-integer step limit; nlohmann::json::exception for a missing field or a wrong type.
void read_settings(const nlohmann::json& settings, PosesStudy& study, const std::string& name);

}  // namespace repose
