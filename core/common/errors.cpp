#include "core/common/errors.hpp"

namespace gr {

namespace {
std::string locate(const std::string& file, std::size_t line, const std::string& message) {
  std::string where = file.empty() ? std::string("<input>") : file;
  if (line > 0) where += ":" + std::to_string(line);
  return where + ": " + message;
}
}  // namespace

InputError::InputError(const std::string& file, std::size_t line, const std::string& message)
    : std::runtime_error(locate(file, line, message)), file_(file), line_(line) {}

}  // namespace gr
