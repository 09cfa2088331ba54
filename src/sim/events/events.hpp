// Internal: the one event locator. Every event of the engine — a vertex reaching the wall in flight or in
// contact, a vertex entering or leaving the ε band, a contact decision changing, the paper's stability test
// passing for a moment — is a root function located by locate() on the motion's dense output (CVODE's root
// functions, SciPy's `events`): the integrator never steps past an event, and the phase decides what the
// event means.
//
// A root function is given to locate() as
//   holds(t)        whether the event's condition holds at t (its sign);
//   clear(a, b)     whether a bound proves that it holds nowhere in (a, b) when it holds at neither end
//                   (a vertex's acceleration, a margin's Lipschitz constant); `monotone` when the interval
//                   is known to hold at most one change of sign (a bracket of a single crossing);
//   margin(t)       optionally, a continuous signed distance to the event (> 0 before, < 0 after), from
//                   which TOMS 748 (Alefeld, Potra and Shi; Boost.Math) brackets a crossing in fewer
//                   evaluations than halving.
// Intervals are examined earliest first, depth first, each halved until it is proved clear or is a bracket
// of the resolution: the earliest instant is found, never a later one, and an event that holds only for a
// moment inside a step is still seen.
#pragma once

#include <array>
#include <boost/math/tools/toms748_solve.hpp>
#include <climits>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "../tolerances.hpp"

namespace repose::sim {

// The search's resolution and bounds, with their reasons, are in the tolerance table (tolerances.hpp).
using tol::kEventResolution;
using tol::kMaxDepth;
using tol::kMaxHalvings;
using tol::kMaxIntervals;
using tol::kPaperHalvings;

struct EventSearch {
  double resolution = 0;       ///< an interval this short (time) is a bracket, or is clear
  int max_halvings = INT_MAX;  ///< ... as is one halved this many times
  int max_intervals = kMaxIntervals;
  bool hi_holds_known = false;  ///< the event is known to hold at the search's upper end
  /// Stop at the first instant examined at which the event holds (an event that may hold only for a
  /// moment: any instant of it will do), instead of bracketing where it begins.
  bool any_instant = false;
};

struct Located {
  enum class Kind {
    none,     ///< the event holds nowhere in the interval (or only at an instant shorter than the resolution)
    bracket,  ///< it begins in (lo, hi]: it holds at hi and not at lo
    instant,  ///< it holds at lo (= hi), an instant examined (EventSearch::any_instant)
    exhausted,  ///< the search hit max_intervals; lo is where it would have gone on
  };
  Kind kind = Kind::none;
  double lo = 0, hi = 0;
  bool found() const { return kind == Kind::bracket || kind == Kind::instant; }
};

/// `clear` for a root function known to change sign at most once in any bracket: an interval whose ends do
/// not hold the event holds none.
inline bool monotone(double, double) { return true; }

struct NoMargin {};

/// Locates the first instant in (lo, hi] at which `holds` does (see the file comment).
template <class Holds, class Clear, class Margin = NoMargin>
Located locate(double lo, double hi, const EventSearch& search, Holds&& holds, Clear&& clear,
               Margin&& margin = {}) {
  if constexpr (!std::is_same_v<std::decay_t<Margin>, NoMargin>) {
    // A crossing of a continuous margin: TOMS 748, then the bracket is snapped to the grid of cells
    // `resolution` wide from lo, the cells halving would end in, and checked with the event test itself:
    // the result depends on the event test alone, not on the round-off of the margins (which differ with
    // the particle's scale), so a run stays the same at any scale.
    const double m_lo = margin(lo), m_hi = margin(hi);
    if (m_lo > 0 && m_hi < 0) {
      boost::uintmax_t iterations = static_cast<boost::uintmax_t>(search.max_halvings);
      const double resolution = search.resolution;
      const auto r = boost::math::tools::toms748_solve(
          margin, lo, hi, m_lo, m_hi, [&](double a, double b) { return b - a <= resolution; }, iterations);
      const double cell = std::floor((r.first - lo) / resolution);
      double a = lo + cell * resolution, b = std::min(hi, a + resolution);
      for (int shift = 0; shift < 4 && a > lo && holds(a); ++shift) {
        b = a;
        a = std::max(lo, a - resolution);
      }
      for (int shift = 0; shift < 4 && b < hi && !holds(b); ++shift) {
        a = b;
        b = std::min(hi, b + resolution);
      }
      if (!holds(a) && holds(b)) return {Located::Kind::bracket, a, b};
    }
  }
  struct Interval {
    double lo, hi;
    bool hi_holds;
    int depth;
  };
  // Intervals still to examine, the earliest on top: each halving pushes two and pops one, so the stack
  // never holds more than the deepest halving plus one. A midpoint is tested when its interval is halved,
  // which is just before its left half is examined.
  std::array<Interval, kMaxDepth + 1> stack;
  std::size_t size = 0;
  stack[size++] = {lo, hi, search.hi_holds_known || holds(hi), 0};
  for (int examined = 0; size > 0 && examined < search.max_intervals; ++examined) {
    const Interval i = stack[--size];
    const bool shortest =
        i.hi - i.lo <= search.resolution || i.depth >= search.max_halvings || i.depth >= kMaxDepth;
    if (i.hi_holds) {
      if (shortest) return {Located::Kind::bracket, i.lo, i.hi};
    } else if (shortest || clear(i.lo, i.hi)) {
      continue;
    }
    const double mid = 0.5 * (i.lo + i.hi);
    const bool mid_holds = holds(mid);
    if (mid_holds && search.any_instant) return {Located::Kind::instant, mid, mid};
    stack[size++] = {mid, i.hi, i.hi_holds, i.depth + 1};
    stack[size++] = {i.lo, mid, mid_holds, i.depth + 1};
  }
  if (size == 0) return {Located::Kind::none, lo, hi};
  return {Located::Kind::exhausted, stack[size - 1].lo, stack[size - 1].lo};
}

}  // namespace repose::sim
