// Cutting a job into work items.
#include <algorithm>

#include "repose/campaign/campaign.hpp"
#include "repose/error.hpp"
#include "repose/poses/ensemble.hpp"

namespace repose {

std::vector<DropRange> remaining_ranges(DropRange wanted, const std::vector<DropRange>& done) {
  std::vector<DropRange> sorted = done;
  std::sort(sorted.begin(), sorted.end(),
            [](const DropRange& a, const DropRange& b) { return a.begin < b.begin; });
  std::vector<DropRange> left;
  std::uint64_t next = wanted.begin;
  for (const DropRange& r : sorted) {
    if (r.begin >= r.end) continue;
    if (r.begin < wanted.begin || r.end > wanted.end)
      throw Error("holds drops [" + std::to_string(r.begin) + ", " + std::to_string(r.end) +
                  ") outside the requested [" + std::to_string(wanted.begin) + ", " +
                  std::to_string(wanted.end) + ")");
    if (r.begin < next) throw Error("holds overlapping drop ranges");
    if (r.begin > next) left.push_back({next, r.begin});
    next = r.end;
  }
  if (next < wanted.end) left.push_back({next, wanted.end});
  return left;
}

std::uint64_t auto_chunk(std::uint64_t drops, int threads) {
  const auto t = static_cast<std::uint64_t>(threads > 0 ? threads : available_cores());
  constexpr std::uint64_t kItemsPerParticle = 64, kMaxChunk = 65536;
  std::uint64_t chunk = (drops + kItemsPerParticle - 1) / kItemsPerParticle;
  chunk = std::min(std::max(chunk, 128 * t), kMaxChunk);
  return std::max<std::uint64_t>(1, std::min(chunk, drops));
}

std::vector<WorkItem> plan_work(const std::vector<std::vector<DropRange>>& remaining,
                                const std::vector<double>& cost_per_drop, std::uint64_t chunk) {
  if (chunk == 0) throw Error("the number of drops per work item must be >= 1");
  if (cost_per_drop.size() != remaining.size()) throw Error("plan_work: one cost per particle needed");
  std::vector<WorkItem> items;
  for (std::size_t p = 0; p < remaining.size(); ++p)
    for (const DropRange& r : remaining[p])
      for (std::uint64_t b = r.begin; b < r.end; b += std::min(chunk, r.end - b))
        items.push_back({static_cast<std::uint32_t>(p), {b, b + std::min(chunk, r.end - b)}});
  const auto cost = [&](const WorkItem& w) {
    return static_cast<double>(w.drops.size()) * cost_per_drop[w.particle];
  };
  std::stable_sort(items.begin(), items.end(),
                   [&](const WorkItem& a, const WorkItem& b) { return cost(a) > cost(b); });
  return items;
}

}  // namespace repose
