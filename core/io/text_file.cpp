#include "core/io/text_file.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <utility>

#include "core/common/errors.hpp"
#include "core/io/input_file.hpp"

namespace gr {

TextFile::TextFile(const std::string& path) : path_(path) {
  require_regular_file(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open file (missing or unreadable)");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  contents_ = buffer.str();
  split_lines();
}

TextFile::TextFile(const std::string& name, std::string contents)
    : path_(name), contents_(std::move(contents)) {
  split_lines();
}

void TextFile::split_lines() {
  const std::string& path = path_;
  if (contents_.find('\0') != std::string::npos)
    throw InputError(path, 0, "binary data where a text file was expected");
  if (contents_.find_first_not_of(" \t\r\n") == std::string::npos)
    throw InputError(path, 0, "file is empty");

  std::string_view all(contents_);
  std::size_t start = 0;
  while (start <= all.size()) {
    std::size_t end = all.find('\n', start);
    if (end == std::string_view::npos) end = all.size();
    std::string_view text = all.substr(start, end - start);
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    lines_.push_back(text);
    if (end == all.size()) break;
    start = end + 1;
  }
}

std::vector<std::string_view> TextFile::split(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

double TextFile::parse_double(std::string_view token, std::size_t line_index) const {
  double value = 0.0;
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (first != last && *first == '+') ++first;
  auto [ptr, ec] = std::from_chars(first, last, value);
  if (ec != std::errc() || ptr != last || first == last)
    fail(line_index, "malformed number '" + std::string(token) + "'");
  if (!std::isfinite(value)) fail(line_index, "non-finite number '" + std::string(token) + "'");
  return value;
}

long long TextFile::parse_integer(std::string_view token, std::size_t line_index) const {
  long long value = 0;
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (first != last && *first == '+') ++first;
  auto [ptr, ec] = std::from_chars(first, last, value);
  if (ec != std::errc() || ptr != last || first == last)
    fail(line_index, "malformed integer '" + std::string(token) + "'");
  return value;
}

void TextFile::fail(std::size_t line_index, const std::string& message) const {
  throw InputError(path_, line_index == std::string::npos ? 0 : line_index + 1, message);
}

}  // namespace gr
