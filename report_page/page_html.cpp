#include "report_page/page_html.hpp"

#include "core/io/atomic_file.hpp"
#include "report_page/page_assets.hpp"

namespace gr {

std::string html_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string json_for_script(const nlohmann::ordered_json& json) {
  // Replacing invalid UTF-8 keeps dump() from throwing on odd bytes in file names.
  const std::string text =
      json.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

std::string html_document(std::string_view title, std::string_view body) {
  std::string page;
  page.reserve(body.size() + page_style().size() + 1024);
  page += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  // The page must never reach the network: the policy forbids every request but inline
  // code and embedded images, so a mistake shows as a console error instead.
  page +=
      "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; "
      "script-src 'unsafe-inline'; style-src 'unsafe-inline'; img-src data:\">\n";
  page += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  page += "<link rel=\"icon\" href=\"data:,\">\n<title>";
  page += html_escape(title);
  page += "</title>\n<style>\n";
  page += page_style();
  page += "</style>\n</head>\n<body>\n";
  page += body;
  page += "</body>\n</html>\n";
  return page;
}

void write_page_file(const std::string& path, const std::string& html) {
  write_file_atomically(path, [&](std::ostream& out) { out << html; });
}

}  // namespace gr
