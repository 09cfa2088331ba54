// The summary of a many-particle job: one row per particle with its most likely rest pose.
#pragma once

#include <string>
#include <vector>

#include "repose/campaign/campaign.hpp"
#include "repose/poses/study.hpp"

namespace repose {

/// `studies[i]` belongs to `particles[i]`; `result_file(i)` names its result file in the tables.
struct CampaignSummary {
  std::vector<CampaignParticle> particles;
  std::vector<PosesStudy> studies;
  std::vector<std::string> result_files;
  double seconds = 0;  ///< wall-clock time of the job (timing)
  int ranks = 1;
  int threads = 0;  ///< per rank
};

/// CSV, one row per particle (no timing, so that reruns compare equal).
std::string summary_csv(const CampaignSummary& summary);
/// A Markdown table, one row per particle (no timing).
std::string summary_markdown(const CampaignSummary& summary);
/// JSON: settings, one object per particle, and a `timing` object.
std::string summary_json(const CampaignSummary& summary);

}  // namespace repose
