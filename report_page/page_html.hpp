#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace gr {

/// `text` with &, <, >, " and ' replaced by character references: safe as element content
/// and inside quoted attributes.
std::string html_escape(std::string_view text);

/// JSON text that is safe inside a <script> element: every '<' is written as \u003c (it
/// can only occur inside strings), so no "</script" or "<!--" can end or change it.
std::string json_for_script(const nlohmann::ordered_json& json);

/// A complete HTML document that opens from disk with no network: a Content-Security-Policy
/// that allows only inline scripts and styles and data: images, no favicon request, and
/// the pages' style sheet. `body` is inserted as it is (already HTML).
std::string html_document(std::string_view title, std::string_view body);

/// Writes a page to `path` atomically.
/// @throw OutputError when it cannot be written.
void write_page_file(const std::string& path, const std::string& html);

}  // namespace gr
