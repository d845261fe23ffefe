#pragma once

#include <string>
#include <vector>

namespace gr {

/// A speed/accuracy benchmark as a page: a table of runs and the plot of time against
/// accuracy.
struct BenchmarkPageData {
  std::string title;
  std::string notes;                           ///< a paragraph under the title (plain text)
  std::vector<std::string> columns;            ///< table header
  std::vector<std::vector<std::string>> rows;  ///< each as many cells as columns (plain text)
  /// Per row: the path of that run's report page relative to the benchmark page, or empty.
  /// The row's cell in link_column links to it.
  std::vector<std::string> row_pages;
  std::size_t link_column = 0;
  std::string plot_png;  ///< bytes of a PNG file; empty: no plot
  std::string plot_caption;
};

/// A self-contained HTML page (the report pages' style, no script): the notes, the table
/// and the plot embedded as a data: URI, so it opens from disk with no network. Links to
/// the runs' pages are relative, for a page kept beside its runs.
/// @throw std::invalid_argument when a row's cell count differs from the columns',
///        row_pages is neither empty nor one per row, or link_column is not a column.
std::string benchmark_page_html(const BenchmarkPageData& data);

/// Writes benchmark_page_html(data) to `path` atomically.
/// @throw std::invalid_argument as benchmark_page_html; OutputError when it cannot be written.
void write_benchmark_page(const std::string& path, const BenchmarkPageData& data);

}  // namespace gr
