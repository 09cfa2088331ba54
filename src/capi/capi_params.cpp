// The C API's settling parameters: set and read by their names in the parameter table (param_table.hpp).
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include "capi_support.hpp"
#include "repose/model/param_table.hpp"

using repose::capi::CodedError;
using repose::capi::guarded;
using repose::capi::require;

namespace {

// The names set_number and set_text take, comma-separated, in the table's order.
std::string accepted() {
  std::string names;
  for (const repose::ParamInfo& info : repose::param_table()) {
    const std::string n = info.name;
    if (n == "drop_height" || n == "drop_speed" ||
        std::holds_alternative<repose::Vec3 repose::SettleParams::*>(info.member))
      continue;
    names += (names.empty() ? "" : ", ") + n;
  }
  return names;
}

// The start state is repose_settler_new's: the parameters that would also set it are not settable here.
const repose::ParamInfo& settable(const char* name) {
  const std::string n = name;
  if (n == "drop_height" || n == "drop_speed" || n == "velocity" || n == "spin")
    throw CodedError(REPOSE_ERROR_BAD_PARAMETER,
                     "'" + n + "' is part of the start state: give it in repose_settler_new's start");
  const repose::ParamInfo* info = repose::find_param(n);
  if (info == nullptr || std::holds_alternative<repose::Vec3 repose::SettleParams::*>(info->member))
    throw CodedError(REPOSE_ERROR_BAD_PARAMETER,
                     "unknown parameter '" + n + "' (accepted: " + accepted() + ")");
  return *info;
}

// A whole number held exactly by a double and by the member's type.
template <class Int>
Int whole(const repose::ParamInfo& info, double value) {
  if (!(value == std::floor(value)) || std::fabs(value) > 9.0e15 ||
      value < static_cast<double>(std::numeric_limits<Int>::min()) ||
      value > static_cast<double>(std::numeric_limits<Int>::max()))
    throw CodedError(REPOSE_ERROR_BAD_PARAMETER, std::string("parameter ") + info.name +
                                                     " must be a whole number, got " + std::to_string(value));
  return static_cast<Int>(value);
}

// Sets the parameter on a copy and validates it, so that a rejected value leaves `params` as it was.
template <class Set>
void set_checked(repose::SettleParams& params, Set&& set) {
  repose::SettleParams trial = params;
  set(trial);
  repose::validate(trial);
  params = trial;
}

void set_number(repose::SettleParams& params, const repose::ParamInfo& info, double value) {
  set_checked(params, [&](repose::SettleParams& p) {
    std::visit(repose::Overloaded{[&](double repose::SettleParams::*m) { p.*m = value; },
                                  [&](long repose::SettleParams::*m) { p.*m = whole<long>(info, value); },
                                  [&](int repose::SettleParams::*m) { p.*m = whole<int>(info, value); },
                                  [&](repose::Vec3 repose::SettleParams::*) {},  // refused by settable()
                                  [&](const repose::ParamChoice&) {
                                    throw CodedError(REPOSE_ERROR_BAD_PARAMETER,
                                                     std::string("parameter ") + info.name +
                                                         " is a choice: set it with repose_params_set_text");
                                  }},
               info.member);
  });
}

}  // namespace

extern "C" {

int repose_params_new(int units, repose_params** params) {
  return guarded("repose_params_new", REPOSE_ERROR_BAD_PARAMETER, [&] {
    require(params, "params");
    if (units != REPOSE_UNITS_SI && units != REPOSE_UNITS_CGS)
      throw CodedError(
          REPOSE_ERROR_BAD_PARAMETER,
          "units must be REPOSE_UNITS_SI (0) or REPOSE_UNITS_CGS (1), got " + std::to_string(units));
    auto* out = new repose_params{};
    out->params.gravity =
        repose::standard_gravity(units == REPOSE_UNITS_SI ? repose::UnitSystem::si : repose::UnitSystem::cgs);
    *params = out;
  });
}

void repose_params_free(repose_params* params) { delete params; }

int repose_params_set_number(repose_params* params, const char* name, double value) {
  return guarded("repose_params_set_number", REPOSE_ERROR_BAD_PARAMETER, [&] {
    require(params, "params");
    require(name, "name");
    set_number(params->params, settable(name), value);
  });
}

int repose_params_set_text(repose_params* params, const char* name, const char* value) {
  return guarded("repose_params_set_text", REPOSE_ERROR_BAD_PARAMETER, [&] {
    require(params, "params");
    require(name, "name");
    require(value, "value");
    const repose::ParamInfo& info = settable(name);
    const std::string text = value;
    if (const auto* choice = std::get_if<repose::ParamChoice>(&info.member)) {
      set_checked(params->params, [&](repose::SettleParams& p) { choice->set(p, text); });
      return;
    }
    // A number as the command line writes it: strtod's whole text ("inf" included), nothing after it.
    char* end = nullptr;
    const double number = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size())
      throw CodedError(REPOSE_ERROR_BAD_PARAMETER,
                       std::string("parameter ") + info.name + " must be a number, got '" + text + "'");
    set_number(params->params, info, number);
  });
}

int repose_params_get_number(const repose_params* params, const char* name, double* value) {
  return guarded("repose_params_get_number", REPOSE_ERROR_BAD_PARAMETER, [&] {
    require(params, "params");
    require(name, "name");
    require(value, "value");
    const repose::ParamInfo* info = repose::find_param(name);
    if (info == nullptr)
      throw CodedError(REPOSE_ERROR_BAD_PARAMETER, std::string("unknown parameter '") + name + "'");
    const repose::SettleParams& p = params->params;
    *value = std::visit(
        repose::Overloaded{[&](double repose::SettleParams::*m) { return p.*m; },
                           [&](long repose::SettleParams::*m) { return static_cast<double>(p.*m); },
                           [&](int repose::SettleParams::*m) { return static_cast<double>(p.*m); },
                           [&](repose::Vec3 repose::SettleParams::*) -> double {
                             throw CodedError(REPOSE_ERROR_BAD_PARAMETER,
                                              std::string("parameter ") + info->name + " is not a number");
                           },
                           [&](const repose::ParamChoice&) -> double {
                             throw CodedError(
                                 REPOSE_ERROR_BAD_PARAMETER,
                                 std::string("parameter ") + info->name + " is a choice, not a number");
                           }},
        info->member);
  });
}

}  // extern "C"
