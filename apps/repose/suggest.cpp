#include "suggest.hpp"

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

namespace repose::cli {

namespace {

// Optimal string alignment distance: insertions, deletions, substitutions and adjacent transpositions.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] != b[j - 1])});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

std::string strip_dashes(const std::string& s) {
  return s.substr(s.find_first_not_of('-') == std::string::npos ? s.size() : s.find_first_not_of('-'));
}

// The long and short names of every option of `app` except help, each with its dashes.
std::vector<std::vector<std::string>> option_names(const CLI::App& app) {
  std::vector<std::vector<std::string>> names;
  for (const CLI::Option* option : app.get_options()) {
    if (option->get_name() == "--help" || option->get_name() == "-h,--help") continue;
    std::vector<std::string> one;
    for (const std::string& l : option->get_lnames()) one.push_back("--" + l);
    for (const std::string& s : option->get_snames()) one.push_back("-" + s);
    if (!one.empty() && one.front() != "--help") names.push_back(one);
  }
  return names;
}

std::string quoted_list(const std::vector<std::string>& items) {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i)
    s += (i == 0 ? "" : i + 1 == items.size() ? " or " : ", ") + items[i];
  return s;
}

// The subcommand the user named (the one CLI11 entered), or nullptr.
const CLI::App* entered_subcommand(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    if (sub->parsed()) return sub;
  return nullptr;
}

}  // namespace

std::vector<std::string> closest(const std::string& typed, const std::vector<std::string>& candidates) {
  const std::string bare = strip_dashes(typed);
  // The nearest by edit distance, if near enough: "--thread" -> "--threads", not also "--threads-max".
  const std::size_t limit = std::max<std::size_t>(1, bare.size() / 3);
  std::size_t best = limit + 1;
  std::vector<std::string> nearest;
  for (const std::string& c : candidates) {
    const std::size_t d = edit_distance(bare, strip_dashes(c));
    if (d < best) nearest.clear(), best = d;
    if (d == best) nearest.push_back(c);
  }
  if (best <= limit) return nearest;
  // Else a name it begins or ends: "--out-dir" -> "--out", "--frame" -> "--frame-dt".
  std::vector<std::string> prefixed;
  for (const std::string& c : candidates) {
    const std::string name = strip_dashes(c);
    if (bare.size() >= 2 && name.size() >= 2 && (name.rfind(bare, 0) == 0 || bare.rfind(name, 0) == 0))
      prefixed.push_back(c);
  }
  return prefixed;
}

std::string parse_error_message(const CLI::App& app, const CLI::ParseError& error, int argc,
                                const char* const* argv) {
  const CLI::App* sub = entered_subcommand(app);
  if (sub == nullptr) {
    // No subcommand entered: the first word that is not an option is a mistyped one, or there is none.
    std::vector<std::string> subcommands;
    for (const CLI::App* s : app.get_subcommands([](const CLI::App*) { return true; }))
      subcommands.push_back(s->get_name());
    for (int i = 1; i < argc; ++i) {
      const std::string word = argv[i];
      if (word.empty() || word[0] == '-') continue;
      const std::vector<std::string> near = closest(word, subcommands);
      return "unknown subcommand '" + word + "'" +
             (near.empty() ? "" : " (did you mean " + quoted_list(near) + "?)") + "; the subcommands are " +
             quoted_list(subcommands) + " (see repose --help)";
    }
    return "a subcommand is required: " + quoted_list(subcommands) + " (see repose --help)";
  }
  const std::string help = " (see repose " + sub->get_name() + " --help)";
  if (dynamic_cast<const CLI::ExtrasError*>(&error) != nullptr) {
    for (const std::string& extra : sub->remaining()) {
      if (extra.size() < 2 || extra[0] != '-') continue;
      const std::string typed = extra.substr(0, extra.find('='));
      std::vector<std::string> candidates;
      const std::vector<std::vector<std::string>> names = option_names(*sub);
      for (const auto& one : names) candidates.insert(candidates.end(), one.begin(), one.end());
      std::vector<std::string> near = closest(typed, candidates);
      // Name an option by all its names: "--drops/-n".
      std::vector<std::string> shown;
      for (const auto& one : names)
        if (std::any_of(one.begin(), one.end(), [&](const std::string& n) {
              return std::find(near.begin(), near.end(), n) != near.end();
            })) {
          std::string joined;
          for (const std::string& n : one) joined += (joined.empty() ? "" : "/") + n;
          shown.push_back(joined);
        }
      return sub->get_name() + ": unknown option " + typed +
             (shown.empty() ? "" : " (did you mean " + quoted_list(shown) + "?)") + help;
    }
  }
  return sub->get_name() + ": " + error.what() + help;
}

}  // namespace repose::cli
