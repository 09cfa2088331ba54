#include "html_page.hpp"

#include "repose/error.hpp"

namespace repose {

namespace {

// A <script> element ends at the first "</script" whatever its type, and "<!--" inside it changes how the
// browser looks for that end; '<' appears in JSON only inside strings, where "\u003c" is the same string.
std::string script_safe_json(const nlohmann::json& data) {
  const std::string text = data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

// Embedded code goes in verbatim; an asset that could end its element early is a build error to catch.
std::string_view script_body(std::string_view name) {
  const std::string_view text = report_asset(name);
  if (text.find("</script") != std::string_view::npos || text.find("<!--") != std::string_view::npos)
    throw Error(std::string("report: the embedded file ") + std::string(name) + " cannot go inside <script>");
  return text;
}

}  // namespace

std::string escape_html(std::string_view text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string base64(std::string_view bytes) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    unsigned word = 0;
    for (std::size_t k = 0; k < 3; ++k)
      word = word << 8 | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k) out += k <= n ? kDigits[(word >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

std::string html_page(const std::string& title, const nlohmann::json& data) {
  std::string page = "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  page += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  page += "<meta name=\"generator\" content=\"repose\">\n";
  page += "<title>" + escape_html(title) + "</title>\n<style>\n";
  page += report_asset("uplot/uPlot.min.css");
  page += "\n";
  page += report_asset("html/report.css");
  page +=
      "</style>\n</head>\n<body>\n<noscript>This report draws itself with JavaScript; allow it to see the "
      "run.</noscript>\n<main id=\"app\"></main>\n";
  page += "<script id=\"repose-data\" type=\"application/json\">" + script_safe_json(data) + "</script>\n";
  page += "<script>";
  page += script_body("uplot/uPlot.iife.min.js");
  page += "</script>\n";
  // three.js is an ES module; the page imports it from a blob of this text (no file or network needed).
  page += "<script id=\"three-source\" type=\"text/plain\">";
  page += script_body("three/three.module.min.js");
  page += "</script>\n<script type=\"module\">\n";
  for (const char* part : {"html/common.js", "html/stage.js", "html/settle.js", "html/poses.js",
                           "html/design.js", "html/paper.js", "html/main.js"})
    page += script_body(part);
  page += "</script>\n";
  // The libraries' licences (MIT) travel with every copy of their code.
  page += "<template id=\"licences\">\n<pre>three.js r170\n" + escape_html(report_asset("three/LICENSE")) +
          "</pre>\n<pre>uPlot 1.6.32\n" + escape_html(report_asset("uplot/LICENSE")) +
          "</pre>\n</template>\n";
  page += "</body>\n</html>\n";
  return page;
}

}  // namespace repose
