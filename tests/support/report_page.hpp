// The data an HTML report embeds, read back as the page's script reads it (tests/output, tests/cli).
#pragma once

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

namespace repose::test {

/// The JSON in the page's <script id="repose-data"> (the writer puts "\u003c" for "<", the same to a JSON
/// parser). Throws if the page has none.
inline nlohmann::json report_page_data(const std::string& page) {
  const std::string open = "<script id=\"repose-data\" type=\"application/json\">";
  const auto begin = page.find(open);
  if (begin == std::string::npos) throw std::runtime_error("the page embeds no repose-data");
  const auto end = page.find("</script>", begin);
  return nlohmann::json::parse(page.substr(begin + open.size(), end - begin - open.size()));
}

}  // namespace repose::test
