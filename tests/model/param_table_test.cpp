// The parameter table (issue 32): the one place the CLI, scenario files, JSON echoes, study settings and
// Python take SettleParams's names, ranges and help from. Each test goes over every entry, so a new entry is
// checked without a new test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <repose/error.hpp>
#include <repose/model/param_table.hpp>
#include <repose/model/scenario.hpp>
#include <set>
#include <string>

namespace repose {
namespace {

// A valid value other than the default, as scenario JSON text, and what it must set.
std::string other_value(const ParamInfo& info, SettleParams& expected) {
  return std::visit(Overloaded{[&](double SettleParams::*m) {
                                 const ParamRange& r = info.range;
                                 const double lo = std::isfinite(r.min) ? r.min : -1;
                                 const double hi = std::isfinite(r.max) ? r.max : lo + 2;
                                 expected.*m = lo + (hi - lo) * 0.25;  // inside: off both bounds
                                 if (expected.*m == SettleParams{}.*m) expected.*m = lo + (hi - lo) * 0.5;
                                 char text[40];
                                 std::snprintf(text, sizeof text, "%.17g", expected.*m);
                                 return std::string(text);
                               },
                               [&](long SettleParams::*m) {
                                 expected.*m = 7;
                                 return std::string("7");
                               },
                               [&](int SettleParams::*m) {
                                 expected.*m = 7;
                                 return std::string("7");
                               },
                               [&](Vec3 SettleParams::*m) {
                                 expected.*m = Vec3(0.5, -1, 0.25);
                                 return std::string("[0.5, -1, 0.25]");
                               },
                               [&](const ParamChoice& c) {
                                 const std::string other = c.names.back() == std::string(c.get(expected))
                                                               ? c.names.front()
                                                               : c.names.back();
                                 c.set(expected, other);
                                 return "\"" + other + "\"";
                               }},
                    info.member);
}

TEST(ParamTable, NamesAreUniqueSnakeCaseAndFound) {
  std::set<std::string> seen;
  for (const ParamInfo& info : param_table()) {
    const std::string name = info.name;
    EXPECT_TRUE(seen.insert(name).second) << name;
    EXPECT_EQ(name.find_first_not_of("abcdefghijklmnopqrstuvwxyz_"), std::string::npos) << name;
    EXPECT_EQ(find_param(name), &info);
    EXPECT_EQ(option_name(info).find('_'), std::string::npos) << name;
  }
  EXPECT_EQ(find_param("dampnig"), nullptr);
  EXPECT_EQ(option_name(*find_param("contact_threshold")), "contact-threshold");
}

TEST(ParamTable, DefaultsAreWrittenAsPeopleWriteThem) {
  const SettleParams d;
  EXPECT_EQ(param_text(*find_param("max_steps"), d), "2e7");
  EXPECT_EQ(param_text(*find_param("tolerance"), d), "1e-9");
  EXPECT_EQ(param_text(*find_param("contact_threshold"), d), "0.05");
  EXPECT_EQ(param_text(*find_param("friction"), d), "inf");
  EXPECT_EQ(param_text(*find_param("integrator"), d), "adaptive");
  EXPECT_EQ(param_text(*find_param("smooth"), d), "auto");
  EXPECT_EQ(param_text(*find_param("velocity"), d), "0,0,0");
  EXPECT_EQ(param_help(*find_param("max_steps")), "Step limit per run (default 2e7)");
  for (const ParamInfo& info : param_table()) {
    const std::string help = param_help(info);
    EXPECT_FALSE(help.empty()) << info.name;
    EXPECT_EQ(help.find('{'), std::string::npos) << info.name << ": " << help;
  }
}

TEST(ParamTable, EveryRangeIsValidatedByName) {
  for (const ParamInfo& info : param_table()) {
    if (std::holds_alternative<ParamChoice>(info.member)) continue;
    SettleParams p;
    const double bad = info.range.min_open ? info.range.min : std::nextafter(info.range.min, -INFINITY);
    std::visit(Overloaded{[&](double SettleParams::*m) { p.*m = bad; },
                          [&](long SettleParams::*m) { p.*m = static_cast<long>(bad); },
                          [&](int SettleParams::*m) { p.*m = static_cast<int>(bad); },
                          [&](Vec3 SettleParams::*m) { (p.*m).y() = NAN; }, [](const ParamChoice&) {}},
               info.member);
    try {
      validate(p);
      ADD_FAILURE() << info.name << " accepted a value outside its range";
    } catch (const Error& e) {
      EXPECT_EQ(
          std::string(e.what()).rfind("parameter " + option_name(info) + " must be " + info.range.text, 0),
          0u)
          << e.what();
    }
  }
}

TEST(ParamTable, EveryScenarioKeySetsItsParameter) {
  for (const ParamInfo& info : param_table()) {
    if (!(info.uses & in_scenario)) continue;
    SettleParams expected;
    const std::string value = other_value(info, expected);
    const Scenario s = parse_scenario(
        R"({"particle": "box:x=1,y=1,z=1", ")" + std::string(info.name) + "\": " + value + "}", "p.json");
    EXPECT_EQ(param_text(info, s.params), param_text(info, expected)) << info.name;
    EXPECT_NE(param_text(info, s.params), param_text(info, SettleParams{})) << info.name;
  }
}

TEST(ParamTable, CopyParamCopiesOnlyItsParameter) {
  for (const ParamInfo& info : param_table()) {
    SettleParams from;
    other_value(info, from);
    SettleParams to;
    copy_param(info, from, to);
    for (const ParamInfo& other : param_table())
      EXPECT_EQ(param_text(other, to), param_text(other, &other == &info ? from : SettleParams{}))
          << info.name << " -> " << other.name;
  }
}

TEST(ParamTable, PythonKeywordsInTheirDocumentedOrder) {
  EXPECT_EQ(
      param_names(in_python),
      "gravity, damping, integrator, dt, tolerance, contact_threshold, line_threshold, smooth, "
      "drop_height, drop_speed, velocity, spin, restitution, friction, restitution_threshold, max_time, "
      "max_steps");
}

}  // namespace
}  // namespace repose
