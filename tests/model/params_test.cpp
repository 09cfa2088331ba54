// SettleParams validation: every documented range at its edges. Each row sets one field of the defaults and
// says whether validate() must accept it; a refusal names the field ("parameter NAME must be ...").
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <repose/error.hpp>
#include <repose/model/params.hpp>
#include <string>
#include <vector>

namespace repose {
namespace {

struct Row {
  const char* field;
  std::function<void(SettleParams&)> set;
  bool accepted;
};

TEST(SettleParamsValidation, EveryRangeHoldsAtItsEdges) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::nan("");
  auto field = [](double SettleParams::*member, double v) {
    return [member, v](SettleParams& p) { p.*member = v; };
  };
  const std::vector<Row> rows = {
      // gravity: a finite positive number
      {"gravity", field(&SettleParams::gravity, 9.81), true},
      {"gravity", field(&SettleParams::gravity, 0.0), false},
      {"gravity", field(&SettleParams::gravity, -9.81), false},
      {"gravity", field(&SettleParams::gravity, inf), false},
      {"gravity", field(&SettleParams::gravity, nan), false},
      // damping: finite, >= 0
      {"damping", field(&SettleParams::damping, 0.0), true},
      {"damping", field(&SettleParams::damping, -1e-300), false},
      {"damping", field(&SettleParams::damping, inf), false},
      // dt: finite, >= 0 (0: automatic)
      {"dt", field(&SettleParams::dt, 0.0), true},
      {"dt", field(&SettleParams::dt, -1e-9), false},
      {"dt", field(&SettleParams::dt, inf), false},
      // contact threshold: a fraction of L in (0, 1)
      {"contact-threshold", field(&SettleParams::contact_threshold, 0.5), true},
      {"contact-threshold", field(&SettleParams::contact_threshold, 0.0), false},
      {"contact-threshold", field(&SettleParams::contact_threshold, 1.0), false},
      {"contact-threshold", field(&SettleParams::contact_threshold, nan), false},
      // line threshold: finite, positive
      {"line-threshold", field(&SettleParams::line_threshold, 1e-12), true},
      {"line-threshold", field(&SettleParams::line_threshold, 0.0), false},
      {"line-threshold", field(&SettleParams::line_threshold, inf), false},
      // drop height and speed: finite, >= 0
      {"drop-height", field(&SettleParams::drop_height, 0.0), true},
      {"drop-height", field(&SettleParams::drop_height, -1e-9), false},
      {"drop-height", field(&SettleParams::drop_height, inf), false},
      {"drop-speed", field(&SettleParams::drop_speed, 0.0), true},
      {"drop-speed", field(&SettleParams::drop_speed, -1e-9), false},
      {"drop-speed", field(&SettleParams::drop_speed, inf), false},
      // max time: finite, >= 0 (0: automatic); max steps and iterations: positive
      {"max-time", field(&SettleParams::max_time, 0.0), true},
      {"max-time", field(&SettleParams::max_time, -1.0), false},
      {"max-time", field(&SettleParams::max_time, inf), false},
      {"max-steps", [](SettleParams& p) { p.max_steps = 1; }, true},
      {"max-steps", [](SettleParams& p) { p.max_steps = 0; }, false},
      {"max-iterations", [](SettleParams& p) { p.max_iterations = 1; }, true},
      {"max-iterations", [](SettleParams& p) { p.max_iterations = 0; }, false},
      // the pseudo-time iteration's tolerance: finite, positive
      {"quaternion-tolerance", field(&SettleParams::quaternion_tolerance, 1e-300), true},
      {"quaternion-tolerance", field(&SettleParams::quaternion_tolerance, 0.0), false},
      {"quaternion-tolerance", field(&SettleParams::quaternion_tolerance, -1e-8), false},
      {"quaternion-tolerance", field(&SettleParams::quaternion_tolerance, inf), false},
      // the adaptive integrator's tolerance: in [1e-14, 1e-3]
      {"tolerance", field(&SettleParams::tolerance, 1e-14), true},
      {"tolerance", field(&SettleParams::tolerance, 1e-3), true},
      {"tolerance", field(&SettleParams::tolerance, 0.99e-14), false},
      {"tolerance", field(&SettleParams::tolerance, 1.01e-3), false},
      {"tolerance", field(&SettleParams::tolerance, nan), false},
  };
  validate(SettleParams{});  // the defaults are valid
  for (const Row& row : rows) {
    SettleParams p;
    row.set(p);
    std::string message = "accepted";
    try {
      validate(p);
    } catch (const Error& e) {
      message = e.what();
    }
    if (row.accepted) {
      EXPECT_EQ(message, "accepted") << row.field;
    } else {
      EXPECT_EQ(message.rfind(std::string("parameter ") + row.field + " must be ", 0), 0u)
          << row.field << ": " << message;
    }
  }
}

}  // namespace
}  // namespace repose
