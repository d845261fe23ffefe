#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace gr {

/// A text input file split into lines, with number parsing that reports the file and
/// line of any fault. Shared by every reader so all input errors read alike.
class TextFile {
 public:
  /// Reads the whole file.
  /// @throw InputError when the file is missing, unreadable, not a regular file (a device
  ///        or FIFO), empty (no non-blank character) or binary (contains a NUL byte).
  explicit TextFile(const std::string& path);
  /// Takes `contents` as the file named `name` (for data already in memory).
  /// @throw InputError when the contents are empty or binary.
  TextFile(const std::string& name, std::string contents);

  const std::string& path() const { return path_; }
  std::size_t line_count() const { return lines_.size(); }
  /// Line `index` (0-based) without its end-of-line characters.
  std::string_view line(std::size_t index) const { return lines_[index]; }

  /// Whitespace-separated tokens of a line.
  static std::vector<std::string_view> split(std::string_view line);

  /// Parses a finite double; `line_index` is 0-based.
  /// @throw InputError on a malformed number, NaN or infinity.
  double parse_double(std::string_view token, std::size_t line_index) const;
  /// Parses a decimal integer (optionally signed).
  /// @throw InputError on a malformed or out-of-range integer.
  long long parse_integer(std::string_view token, std::size_t line_index) const;

  /// Throws an InputError at the given 0-based line (or the whole file when npos).
  [[noreturn]] void fail(std::size_t line_index, const std::string& message) const;

 private:
  void split_lines();

  std::string path_;
  std::string contents_;
  std::vector<std::string_view> lines_;
};

}  // namespace gr
