// `repose design --model tossed`: the toss's options (the same names as `repose poses`), their checks, and
// the tossed design's summary (design_toss_cli.cpp).
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>

#include "physics_options.hpp"
#include "repose/design/design.hpp"
#include "repose/design/toss_design.hpp"

namespace repose::cli {

struct TossCliOptions {
  PhysicsOptions
      physics;  // --units, the engine's and the impacts' parameters (not --tolerance: the design's)
  TossDistributionOptions toss;
  std::uint64_t drops = 20000, check_drops = 10000, seed = 1;
  int threads = 0;
  int iterations = 12;
};

/// Registers the toss's options on `sub`.
void add_toss_options(CLI::App& sub, TossCliOptions& o);

/// The tossed design's options from the given ones (throws repose::Error naming an option out of range).
TossDesignOptions toss_design_options(const TossCliOptions& o, const CLI::App& sub,
                                      const DesignOptions& shape);

/// Throws repose::Error naming the first toss option given to a quasi-static design.
void reject_toss_options(const CLI::App& sub);

/// The tossed design's table: per outcome the target, both designs' tossed estimates on the check drops with
/// their intervals, the χ² tests, the settles.
void print_toss_design(const DesignTarget& target, const TossDesignOptions& options,
                       const TossDesignResult& r);

}  // namespace repose::cli
