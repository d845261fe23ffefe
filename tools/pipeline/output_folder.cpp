#include "tools/pipeline/output_folder.hpp"

#include <filesystem>

#include "core/common/errors.hpp"

namespace gr {

void prepare_output_folder(const std::string& out_dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec || !fs::is_directory(out_dir))
    throw OutputError(out_dir + ": cannot create output folder" +
                      (ec ? ": " + ec.message() : std::string()));
}

}  // namespace gr
