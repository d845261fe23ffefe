#include "core/io/input_file.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "core/common/errors.hpp"

namespace gr {

void require_regular_file(const std::string& path, std::uintmax_t max_bytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status))
    throw InputError(path, 0, "cannot open file (missing or unreadable)");
  if (!fs::is_regular_file(status))
    throw InputError(path, 0,
                     fs::is_directory(status)
                         ? "is a folder, not a file"
                         : "is not a regular file (a device, FIFO or socket cannot be read)");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > max_bytes)
    throw InputError(path, 0,
                     fmt::format("is {:.1f} MB, more than the {:.1f} MB allowed (--max-input-mb)",
                                 static_cast<double>(size) / 1048576.0,
                                 static_cast<double>(max_bytes) / 1048576.0));
}

}  // namespace gr
