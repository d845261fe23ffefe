#include "report_page/benchmark_page.hpp"

#include <stdexcept>

#include "report_page/mesh_encoding.hpp"
#include "report_page/page_html.hpp"

namespace gr {

std::string benchmark_page_html(const BenchmarkPageData& data) {
  if (!data.row_pages.empty() && data.row_pages.size() != data.rows.size())
    throw std::invalid_argument("benchmark page: row_pages needs one entry per row");
  if (!data.row_pages.empty() && data.link_column >= data.columns.size())
    throw std::invalid_argument("benchmark page: link_column is not a column");
  std::string body = "<header><h1>" + html_escape(data.title) + "</h1>";
  if (!data.notes.empty()) body += "<p class=\"subtitle\">" + html_escape(data.notes) + "</p>";
  body += "</header>\n<main class=\"bench\">\n";
  if (!data.plot_png.empty())
    body += "<figure><img alt=\"" + html_escape(data.plot_caption) +
            "\" src=\"data:image/png;base64," + base64_encode(data.plot_png) + "\"><figcaption>" +
            html_escape(data.plot_caption) + "</figcaption></figure>\n";
  body += "<table class=\"results\">\n<tr>";
  for (const auto& c : data.columns) body += "<th>" + html_escape(c) + "</th>";
  body += "</tr>\n";
  for (std::size_t r = 0; r < data.rows.size(); ++r) {
    const auto& row = data.rows[r];
    if (row.size() != data.columns.size())
      throw std::invalid_argument("benchmark page: row " + std::to_string(r) + " has " +
                                  std::to_string(row.size()) + " cells for " +
                                  std::to_string(data.columns.size()) + " columns");
    body += "<tr>";
    for (std::size_t c = 0; c < row.size(); ++c) {
      const bool link =
          c == data.link_column && !data.row_pages.empty() && !data.row_pages[r].empty();
      body += "<td>";
      body += link ? "<a href=\"" + html_escape(data.row_pages[r]) + "\">" + html_escape(row[c]) +
                         "</a>"
                   : html_escape(row[c]);
      body += "</td>";
    }
    body += "</tr>\n";
  }
  body += "</table>\n</main>\n";
  return html_document(data.title, body);
}

void write_benchmark_page(const std::string& path, const BenchmarkPageData& data) {
  write_page_file(path, benchmark_page_html(data));
}

}  // namespace gr
