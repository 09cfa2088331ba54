// The frame every HTML report shares: the embedded libraries and page code (compiled into the library from
// src/output/html/ and third_party/; see src/CMakeLists.txt), the data as JSON, and the text escapes that
// keep the page well formed.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace repose {

/// The text of an embedded file by its name ("three/three.module.min.js", "html/settle.js", ...). Throws
/// repose::Error for an unknown name.
std::string_view report_asset(std::string_view name);

/// The whole page: `title`, the styles, `data` as JSON, the libraries and the page code.
std::string html_page(const std::string& title, const nlohmann::json& data);

/// `text` safe inside an HTML element or attribute (&, <, >, " escaped).
std::string escape_html(std::string_view text);

/// Standard base64 (RFC 4648, with padding) of `bytes`.
std::string base64(std::string_view bytes);

}  // namespace repose
