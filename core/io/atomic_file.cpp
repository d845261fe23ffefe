#include "core/io/atomic_file.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include <unistd.h>

#include "core/common/errors.hpp"

namespace gr {

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
    throw OutputError(path + ": output folder '" + folder.string() + "' does not exist");

  std::random_device entropy;
  const fs::path temporary = folder / ("." + target.filename().string() + ".tmp" +
                                       std::to_string(getpid()) + "_" + std::to_string(entropy()));
  try {
    {
      std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
      if (!out) throw OutputError(path + ": cannot write in folder '" + folder.string() + "'");
      write(out);
      out.flush();
      if (!out) throw OutputError(path + ": write failed (disk full?)");
    }
    fs::rename(temporary, target, ec);
    if (ec) throw OutputError(path + ": cannot rename temporary file: " + ec.message());
  } catch (...) {
    fs::remove(temporary, ec);
    throw;
  }
}

}  // namespace gr
