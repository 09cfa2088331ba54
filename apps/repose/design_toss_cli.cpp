// design_toss_cli.hpp.
#include "design_toss_cli.hpp"

#include <cstdio>
#include <iostream>
#include <string>

#include "cli_numbers.hpp"
#include "format.hpp"
#include "repose/error.hpp"

namespace repose::cli {

namespace {

// The options that only a tossed design reads.
constexpr const char* kTossOnly[] = {"--units",
                                     "--damping",
                                     "--damping-ratio",
                                     "--integrator",
                                     "--dt",
                                     "--drop-height",
                                     "--drop-speed",
                                     "--max-time",
                                     "--max-steps",
                                     "--restitution",
                                     "--friction",
                                     "--velocity-max",
                                     "--restitution-threshold",
                                     "--spin-max",
                                     "--drops",
                                     "--check-drops",
                                     "--seed",
                                     "--threads",
                                     "--toss-iterations",
                                     "--contact-threshold",
                                     "--line-threshold",
                                     "--smooth"};

std::string interval(const std::array<double, 2>& ci) {
  char s[48];
  std::snprintf(s, sizeof s, "[%.4f, %.4f]", ci[0], ci[1]);
  return s;
}

}  // namespace

void add_toss_options(CLI::App& sub, TossCliOptions& o) {
  o.physics.skip = {"tolerance"};  // the design's own --tolerance
  sub.add_option("--units", o.physics.units, "Tossed: si (m, kg, s; g = 9.81; default) or cgs (cm, g, s)")
      ->check(CLI::IsMember({"si", "cgs"}));
  add_param_options(
      sub, o.physics, CliGroup::physics,
      {{"damping", "Tossed: damping coefficient C of Eq 4 ({unit}); overrides --damping-ratio"}});
  add_impact_options(sub, o.physics);
  add_toss_distribution_options(sub, o.toss, "Tossed: ");
  sub.add_option(
         "--drops", o.drops,
         "Tossed: drops per estimate, the same drops at every iterate (common random numbers; default "
         "20000)")
      ->check(whole_number(1));
  sub.add_option(
         "--check-drops", o.check_drops,
         "Tossed: further drops, never seen by the optimiser, that check both designs (default 10000)")
      ->check(whole_number(1));
  sub.add_option("--seed", o.seed,
                 "Tossed: drop i's orientation and toss depend only on (seed, i) (default 1)")
      ->check(whole_number(0));
  sub.add_option("--threads", o.threads,
                 "Tossed: worker threads (default 0: all cores; results do not depend on it)");
  sub.add_option("--toss-iterations", o.iterations,
                 "Tossed: at most this many quasi-Newton steps, each one tossed estimate (default 12)");
}

TossDesignOptions toss_design_options(const TossCliOptions& o, const CLI::App& sub,
                                      const DesignOptions& shape) {
  const auto given = [&](const char* option) { return sub.count(option) > 0; };
  if (o.threads < 0)
    throw Error("option --threads must be >= 0 (0 = all cores), got " + std::to_string(o.threads));
  if (o.iterations < 0)
    throw Error("option --toss-iterations must be >= 0, got " + std::to_string(o.iterations));
  TossDesignOptions out;
  out.shape = shape;
  out.max_iterations = o.iterations;
  TossModel& m = out.model;
  m.drops = o.drops;
  m.check_drops = o.check_drops;
  m.threads = o.threads;
  StudySettings& s = m.settings;
  s.seed = o.seed;
  s.method = PoseMethod::dynamic;
  o.physics.apply_given(sub, s.params);
  s.params.gravity = standard_gravity(o.physics.unit_system());
  s.damping_given = given("--damping");
  if (!s.damping_given) s.params.damping = 0;  // from the ratio, once each design's particle is known
  validate(s.params);
  apply_toss_distribution(o.toss, s);
  return out;
}

void reject_toss_options(const CLI::App& sub) {
  for (const char* option : kTossOnly)
    if (sub.count(option) > 0)
      throw Error(
          std::string("design: ") + option +
          " sets the toss, which a quasi-static design does not use; add --model tossed or remove it");
}

void print_toss_design(const DesignTarget& target, const TossDesignOptions& options,
                       const TossDesignResult& r) {
  const auto& qs = r.check_quasi_static;
  const auto& tossed = r.check;
  std::cout << "\ntossed (drops " << options.model.drops << ".."
            << options.model.drops + options.model.check_drops - 1
            << ", never seen by the optimiser; 95% Wilson intervals)\n";
  std::cout << "outcome  target    quasi-static design tossed      tossed design\n";
  char line[200];
  const std::size_t k = target.outcomes.size();
  for (std::size_t o = 0; o < k + 2; ++o) {
    const double t = o < k ? target.outcomes[o].probability : 0.0;
    const std::string name = o < k ? std::to_string(o + 1) : o == k ? "other" : "no rest";
    std::snprintf(line, sizeof line, "%-8s %.5f   %.5f %-20s %.5f %-20s\n", name.c_str(), t,
                  qs.probability[o], interval(qs.ci95[o]).c_str(), tossed.probability[o],
                  interval(tossed.ci95[o]).c_str());
    std::cout << line;
  }
  std::snprintf(line, sizeof line,
                "chi-square against the target (%d degrees of freedom): quasi-static design p = %.3g, tossed "
                "design p = %.3g\n",
                tossed.dof, qs.p_value, tossed.p_value);
  std::cout << line;
  std::cout << (r.reached() ? "reached" : "NOT reached") << " on the common drops after " << r.history.size()
            << " tossed estimates ("
            << (r.stop == "converged"
                    ? "as close as a typical sample of the target: chi-square below its median"
                : r.stop == "stalled" ? "stalled: no shorter step lowered the tossed error"
                                      : "--toss-iterations reached")
            << "); every target inside its interval on the check drops: "
            << (tossed.all_within_ci95 ? "yes" : "no")
            << ", in its simultaneous interval (Bonferroni over the " << target.outcomes.size()
            << " outcomes): " << (tossed.all_within_simultaneous ? "yes" : "no")
            << "; within the fit's noise and the check's (the design was fitted on " << tossed.fit_drops
            << " drops): " << (tossed.all_within_fit_and_check ? "yes" : "no")
            << ", simultaneous: " << (tossed.all_within_fit_and_check_simultaneous ? "yes" : "no") << "; "
            << r.settles << " tossed settles\n";
}

}  // namespace repose::cli
