#include "repose/model/param_table.hpp"

#include <array>
#include <cstdio>
#include <cstring>

namespace repose {

namespace {

// Choices: the names in the order messages list them, and the conversions params.hpp defines.
constexpr const char* kIntegrators[] = {"paper", "adaptive"};
constexpr const char* kSmoothModes[] = {"auto", "on", "off"};

const ParamChoice kIntegrator{
    kIntegrators, [](const SettleParams& p) { return to_string(p.integrator); },
    [](SettleParams& p, const std::string& name) { p.integrator = parse_integrator(name); }};
const ParamChoice kSmooth{
    kSmoothModes, [](const SettleParams& p) { return to_string(p.smooth); },
    [](SettleParams& p, const std::string& name) { p.smooth = parse_smooth_mode(name); }};

// Written everywhere a parameter can be (gravity and a few others are not: see their entries).
constexpr unsigned kEverywhere = in_scenario | in_summary | in_study | in_python;
constexpr ParamRange kAtLeastZero{.min = 0, .min_open = false, .text = "a finite number >= 0"};
constexpr ParamRange kZeroIsAutomatic{
    .min = 0, .min_open = false, .text = "a finite positive number (or 0 for automatic)"};
constexpr ParamRange kFinite{.text = "finite in every component"};

// The order is --help's and the messages' (Python lists its keywords in it); study files and JSON echoes
// sort their keys, so it does not change them.
const std::array<ParamInfo, 19> kTable = {{
    {.name = "gravity",
     .unit = "length/time^2",
     .member = &SettleParams::gravity,
     .range = {.min = 0, .text = "a finite positive number"},
     .uses = in_summary | in_study | in_python,  // files and the CLI give it as their unit system
     .help = "Magnitude of g, along -z ({unit}; 9.81 for si, 981 for cgs)"},
    {.name = "damping",
     .unit = "mass*length^2/time",
     .member = &SettleParams::damping,
     .range = kAtLeastZero,
     .uses = kEverywhere,
     .cli = CliGroup::physics,
     .help = "Damping coefficient C of Eq 4 ({unit}; default {default})"},
    {.name = "integrator",
     .unit = "",
     .member = kIntegrator,
     .uses = kEverywhere | study_optional,  // older files: the paper's (read_settings)
     .cli = CliGroup::physics,
     .help =
         "Rotation phases: adaptive (Dormand-Prince 5(4) with events located on its dense output) or paper "
         "(the paper's fixed step with its pseudo-time iteration); default {default}"},
    {.name = "dt",
     .unit = "time",
     .member = &SettleParams::dt,
     .range = kZeroIsAutomatic,
     .uses = kEverywhere,  // the summary echoes the step used (report.cpp)
     .cli = CliGroup::physics,
     .help = "paper: the time step; adaptive: the longest step ({unit}; 0 or unset: automatic, "
             "1e-3*sqrt(L/g) for paper, 0.2*sqrt(L/g) for adaptive)"},
    {.name = "tolerance",
     .unit = "1",
     .member = &SettleParams::tolerance,
     .range = {.min = 1e-14, .max = 1e-3, .min_open = false, .max_open = false, .text = "in [1e-14, 1e-3]"},
     .uses = kEverywhere | study_optional,
     .cli = CliGroup::physics,
     .help = "adaptive: local error bound per step, relative to L and sqrt(L/g) (default {default})"},
    {.name = "contact_threshold",
     .unit = "L",
     .member = &SettleParams::contact_threshold,
     .range = {.min = 0, .max = 1, .text = "a fraction of L in (0, 1)"},
     .uses = kEverywhere,
     .cli = CliGroup::physics,
     .help = "Contact threshold as a fraction of L (default {default}, as in the paper)"},
    {.name = "line_threshold",
     .unit = "L^2",
     .member = &SettleParams::line_threshold,
     .range = {.min = 0, .text = "a finite positive fraction of L^2"},
     .uses = kEverywhere,
     .cli = CliGroup::physics,
     .help = "Line vs surface: RSS of the best-fit line below this fraction of L^2 (default {default})"},
    {.name = "smooth",
     .unit = "",
     .member = kSmooth,
     .uses = in_scenario | in_study | in_python,  // the summary says whether the particle was treated smooth
     .cli = CliGroup::physics,
     .help = "Smooth-particle model: auto | on | off (default {default})",
     .study_key = "smooth_mode"},
    {.name = "drop_height",
     .unit = "length",
     .member = &SettleParams::drop_height,
     .range = kAtLeastZero,
     .uses = kEverywhere,
     .cli = CliGroup::physics,
     .help =
         "Initial height of the lowest point above the wall ({unit}; default {default}: touching, at rest)"},
    {.name = "drop_speed",
     .unit = "length/time",
     .member = &SettleParams::drop_speed,
     .range = kAtLeastZero,
     .uses = kEverywhere,
     .cli = CliGroup::physics,
     .help = "Initial downward speed ({unit}; default {default})"},
    {.name = "velocity",
     .unit = "length/time",
     .member = &SettleParams::velocity,
     .range = kFinite,
     .uses = in_scenario | in_summary | in_python,  // a study draws each drop's (velocity_max)
     .cli = CliGroup::toss,
     .help = "A toss: the centre of mass's initial velocity X,Y,Z (world frame, {unit}; z adds to "
             "-drop-speed)"},
    {.name = "spin",
     .unit = "rad/time",
     .member = &SettleParams::spin,
     .range = kFinite,
     .uses = in_scenario | in_summary | in_python,  // a study draws each drop's (spin_max)
     .cli = CliGroup::toss,
     .help = "A toss: the initial angular velocity X,Y,Z (world frame, {unit})"},
    {.name = "restitution",
     .unit = "1",
     .member = &SettleParams::restitution,
     .range = {.min = 0, .max = 1, .min_open = false, .max_open = false, .text = "in [0, 1]"},
     .uses = kEverywhere | study_optional,  // older files: 0, no rebound
     .cli = CliGroup::impact,
     .help = "Impacts: Stronge's energetic coefficient of restitution E in [0, 1] (default {default}: no "
             "rebound, the paper's touch)"},
    {.name = "friction",
     .unit = "1",
     .member = &SettleParams::friction,
     .range = {.min = 0,
               .max = INFINITY,
               .min_open = false,
               .max_open = false,
               .text = "a number >= 0 or inf (no slip)"},
     .uses = kEverywhere | study_optional,  // older files: no slip
     .cli = CliGroup::impact,
     .help =
         "Coulomb's friction coefficient mu >= 0 at impacts and, after the landing, in the frictional "
         "contact phase (slip, stick and lift-off); inf: no slip, the paper's rotation (default {default})"},
    {.name = "restitution_threshold",
     .unit = "length/time",
     .member = &SettleParams::restitution_threshold,
     .range = kAtLeastZero,
     .uses = kEverywhere | study_optional,  // older files: 0, E at every speed
     .cli = CliGroup::impact,
     .help = "Impacts slower than this normal approach speed ({unit}) are plastic, E = 0 (a cut-off like "
             "Bullet's 0.2 m/s; default {default}: E at every speed)"},
    {.name = "max_time",
     .unit = "time",
     .member = &SettleParams::max_time,
     .range = kZeroIsAutomatic,
     .uses = in_scenario | in_study | in_python,
     .cli = CliGroup::physics,
     .help = "Simulated-time limit per run ({unit}; 0 or unset: automatic, 2000*sqrt(L/g) plus the fall "
             "time)"},
    {.name = "max_steps",
     .unit = "steps",
     .member = &SettleParams::max_steps,
     .range = {.min = 0, .text = "positive"},
     .uses = in_study | in_python,  // not a scenario's: a case is defined by its physics
     .cli = CliGroup::physics,
     .help = "Step limit per run (default {default})"},
    // The pseudo-time iteration's own controls (--integrator paper): validated, not exposed.
    {.name = "quaternion_tolerance",
     .unit = "1",
     .member = &SettleParams::quaternion_tolerance,
     .range = {.min = 0, .text = "a finite positive number"},
     .help = "Convergence of the pseudo-time iteration (Eqs 12-16; default {default})"},
    {.name = "max_iterations",
     .unit = "iterations",
     .member = &SettleParams::max_iterations,
     .range = {.min = 0, .text = "positive"},
     .help = "Bound on pseudo-time iterations per step (default {default})"},
}};

// "%g" without its exponent's padding: 2e7 and 1e-9, as the help texts always wrote them.
std::string short_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  std::string s = buf;
  const auto e = s.find('e');
  if (e == std::string::npos) return s;
  std::string exponent = s.substr(e + 1);
  const bool negative = exponent[0] == '-';
  exponent.erase(0, exponent.find_first_not_of("+-0"));
  return s.substr(0, e + 1) + (negative ? "-" : "") + (exponent.empty() ? "0" : exponent);
}

void replace_all(std::string& s, std::string_view from, const std::string& to) {
  for (auto at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
}

}  // namespace

std::span<const ParamInfo> param_table() { return kTable; }

const ParamInfo* find_param(std::string_view name) {
  for (const ParamInfo& info : kTable)
    if (name == info.name) return &info;
  return nullptr;
}

std::string option_name(const ParamInfo& info) {
  std::string name = info.name;
  for (char& c : name)
    if (c == '_') c = '-';
  return name;
}

void copy_param(const ParamInfo& info, const SettleParams& from, SettleParams& to) {
  std::visit(Overloaded{[&](const ParamChoice& c) { c.set(to, c.get(from)); },
                        [&](auto member) { to.*member = from.*member; }},
             info.member);
}

std::string param_text(const ParamInfo& info, const SettleParams& p) {
  return std::visit(Overloaded{[&](double SettleParams::*m) { return short_number(p.*m); },
                               [&](long SettleParams::*m) { return short_number(static_cast<double>(p.*m)); },
                               [&](int SettleParams::*m) { return short_number(p.*m); },
                               [&](Vec3 SettleParams::*m) {
                                 const Vec3& v = p.*m;
                                 return short_number(v.x()) + "," + short_number(v.y()) + "," +
                                        short_number(v.z());
                               },
                               [&](const ParamChoice& c) { return std::string(c.get(p)); }},
                    info.member);
}

std::string param_help(const ParamInfo& info, std::string_view help) {
  std::string text(help.empty() ? std::string_view(info.help) : help);
  replace_all(text, "{default}", param_text(info, SettleParams{}));
  replace_all(text, "{unit}", info.unit);
  return text;
}

std::string param_names(unsigned uses) {
  std::string names;
  for (const ParamInfo& info : kTable)
    if ((info.uses & uses) == uses) names += (names.empty() ? "" : ", ") + std::string(info.name);
  return names;
}

}  // namespace repose
