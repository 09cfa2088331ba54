// Bullet at its best (issue 35, deliverable 1): its fixed step chosen per shape as the largest candidate
// whose rest-pose histogram agrees with its own finest step's within sampling error.
//
// Agreement: a permutation test of homogeneity of the two histograms (the same N drops at two steps; bins are
// repose's rest poses plus "no rest"), p ≥ kAgreementLevel, and the same test on the drops that rest against
// those that do not (agrees() below). Its statistic is Pearson's χ² over every bin
// (for two samples of one size, Σ (a − b)² / (a + b)), its null distribution the 2N outcomes split at random
// into two halves kPermutations times (seeded): exact for small counts, where pooling bins would hide a
// difference such as 8 drops that never rest against none. The test treats the two runs as independent
// samples; they are paired (the same starts), which makes their difference smaller than independent
// samples' would be, so the test is lenient: it lets Bullet take the coarser, cheaper step when in doubt —
// the choice fair to Bullet. The number of drops sets the test's power, as it sets what a user running that
// many drops could tell apart.
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

namespace peer {

// Bullet's candidate steps (s), coarsest first: 1/60 s is Bullet's default; the finest is the reference.
inline const std::vector<double> kCandidateSteps = {1.0 / 60, 1.0 / 120, 1.0 / 240, 1.0 / 480, 1.0 / 1000};
inline constexpr double kAgreementLevel = 0.05;

struct Homogeneity {
  double chi2 = 0;  // Pearson's statistic over the bins with a count
  int bins = 0;     // bins with a count in either histogram
  double p = 1;     // permutation p-value (Monte Carlo standard error ≤ 0.005 at p = 0.05)
};

inline constexpr int kPermutations = 10000;

// The permutation test of homogeneity of two histograms of the same total N.
inline Homogeneity homogeneity(const std::vector<std::uint64_t>& a, const std::vector<std::uint64_t>& b) {
  const auto chi2 = [](const std::vector<std::uint64_t>& x, const std::vector<std::uint64_t>& y) {
    double sum = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double d = static_cast<double>(x[i]) - static_cast<double>(y[i]);
      if (x[i] + y[i] > 0) sum += d * d / static_cast<double>(x[i] + y[i]);
    }
    return sum;
  };
  Homogeneity h;
  h.chi2 = chi2(a, b);
  std::vector<int> outcomes;  // the 2N drops' bins
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] + b[i] > 0) ++h.bins;
    outcomes.insert(outcomes.end(), a[i] + b[i], static_cast<int>(i));
  }
  if (h.bins < 2) return h;
  const std::size_t n = outcomes.size() / 2;
  std::mt19937_64 bits(20261128);
  std::vector<std::uint64_t> x(a.size()), y(a.size());
  int as_large = 0;
  for (int k = 0; k < kPermutations; ++k) {
    // The first n of a random permutation (Fisher–Yates, stopped at n) are the first sample.
    for (std::size_t i = 0; i < n; ++i) std::swap(outcomes[i], outcomes[i + bits() % (outcomes.size() - i)]);
    std::fill(x.begin(), x.end(), 0);
    std::fill(y.begin(), y.end(), 0);
    for (std::size_t i = 0; i < outcomes.size(); ++i)
      ++(i < n ? x : y)[static_cast<std::size_t>(outcomes[i])];
    if (chi2(x, y) >= h.chi2 - 1e-9) ++as_large;
  }
  h.p = (1.0 + as_large) / (1.0 + kPermutations);
  return h;
}

// Whether Bullet's histogram at a step agrees with its finest step's: the poses and "no rest" together, and
// the fraction of drops that come to rest alone (a drop that never rests has no answer; in the histogram test
// a handful of them weigh little against many bins).
inline std::vector<std::uint64_t> rest_or_not(const std::vector<std::uint64_t>& h) {
  return {std::accumulate(h.begin(), h.end() - 1, std::uint64_t{0}), h.back()};
}

inline bool agrees(const std::vector<std::uint64_t>& step, const std::vector<std::uint64_t>& finest) {
  return homogeneity(step, finest).p >= kAgreementLevel &&
         homogeneity(rest_or_not(step), rest_or_not(finest)).p >= kAgreementLevel;
}

// The index in `histograms` (one per step, coarsest first, the last the finest, each with "no rest" as its
// last bin) of the largest step that agrees with the finest.
inline std::size_t chosen_step(const std::vector<std::vector<std::uint64_t>>& histograms) {
  for (std::size_t i = 0; i + 1 < histograms.size(); ++i)
    if (agrees(histograms[i], histograms.back())) return i;
  return histograms.size() - 1;
}

}  // namespace peer
