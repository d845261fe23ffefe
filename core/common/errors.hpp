#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace gr {

/// Bad input: a missing, unreadable or malformed file, or inconsistent inputs.
/// The message names the file and, where it applies, the 1-based line.
class InputError : public std::runtime_error {
 public:
  /// @param line 1-based line number, or 0 when no single line is at fault.
  InputError(const std::string& file, std::size_t line, const std::string& message);
  const std::string& file() const { return file_; }
  std::size_t line() const { return line_; }

 private:
  std::string file_;
  std::size_t line_;
};

/// An output file or folder that cannot be written.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace gr
